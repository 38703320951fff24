;; Octahedron: exact. Folded into the positive octant, the surface is the face
;; x + y + z = :size. When the point's projection onto that plane falls inside the face
;; the distance is to the plane; otherwise the projection is past one edge (a vertex
;; region ends on that edge too) and the distance is to that edge's segment.

{:kind :octahedron
 :doc "Regular octahedron with its corners on the axes at distance :size."
 :params [{:name :size :type :positive :default 1}]
 :class :exact
 :args [{:name :s :type :float}]
 :pack (fn [o] [o.size])
 :glsl-name "sdOctahedron"
 ;; The distance once, in Fennel: src/sdf/translate.fnl writes :glsl and :cpu from it.
 :fennel "(fn [x y z s]
  ;; Distance from (a, b, c) to the segment from (0, s, 0) to (0, 0, s).
  (fn edge [a b c s]
    (let [k (math.max 0 (math.min s (* 0.5 (+ (- c b) s))))
          v (+ (- b s) k)
          w (- c k)]
      (math.sqrt (+ (* a a) (* v v) (* w w)))))
  (let [ax (math.abs x) ay (math.abs y) az (math.abs z)
        m (- (+ ax ay az) s)]
    (if (< (* 3 ax) m) (edge ax ay az s)
        (< (* 3 ay) m) (edge ay az ax s)
        (< (* 3 az) m) (edge az ax ay s)
        (* m 0.5773502691896258))))"
 :bounds (fn [o] [o.size o.size o.size])}

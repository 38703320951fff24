;; Cheap octahedron: a bound. The octahedron with vertices :size from the centre on the
;; axes is |x| + |y| + |z| <= s; (|x| + |y| + |z| - s) / sqrt(3) is the distance to the
;; nearest face plane, exact inside and over faces but less than the distance near
;; edges and vertices (up to sqrt(3) times less straight out from a vertex).

{:kind :cheap-octahedron
 :doc "Octahedron with vertices :size from the centre on the axes (fast bound)."
 :params [{:name :size :type :positive :default 1}]
 :class :bound
 :args [{:name :s :type :float}]
 :pack (fn [o] [o.size])
 :glsl-name "sdCheapOctahedron"
 ;; The distance once, in Fennel: src/sdf/translate.fnl writes :glsl and :cpu from it.
 :fennel "(fn [x y z s]
  (* (- (+ (math.abs x) (math.abs y) (math.abs z)) s) 0.5773502691896258))"
 :bounds (fn [o] [o.size o.size o.size])}

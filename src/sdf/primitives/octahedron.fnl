;; Octahedron: exact. Folded into the positive octant, the surface is the face
;; x + y + z = :size. When the point's projection onto that plane falls inside the face
;; the distance is to the plane; otherwise the projection is past one edge (a vertex
;; region ends on that edge too) and the distance is to that edge's segment.
(local {: sqrt : max : min : abs} math)

(local inv-sqrt3 (/ 1 (sqrt 3)))

;; Distance from (a, b, c) to the segment from (0, s, 0) to (0, 0, s).
(fn edge [a b c s]
  (let [k (max 0 (min s (* 0.5 (+ (- c b) s))))
        v (+ (- b s) k)
        w (- c k)]
    (sqrt (+ (* a a) (* v v) (* w w)))))

{:kind :octahedron
 :doc "Regular octahedron with its corners on the axes at distance :size."
 :params [{:name :size :type :positive :default 1}]
 :class :exact
 :args [{:name :s :type :float}]
 :pack (fn [o] [o.size])
 :glsl-name "sdOctahedron"
 :glsl "float sdOctahedron(vec3 p, float s) {
    p = abs(p);
    float m = p.x + p.y + p.z - s;
    vec3 q;
    if (3.0 * p.x < m) q = p.xyz;
    else if (3.0 * p.y < m) q = p.yzx;
    else if (3.0 * p.z < m) q = p.zxy;
    else return m * 0.5773502691896258;
    float k = clamp(0.5 * (q.z - q.y + s), 0.0, s);
    return length(vec3(q.x, q.y - s + k, q.z - k));
}"
 :cpu (fn [x y z s]
        (let [ax (abs x) ay (abs y) az (abs z)
              m (- (+ ax ay az) s)]
          (if (< (* 3 ax) m) (edge ax ay az s)
              (< (* 3 ay) m) (edge ay az ax s)
              (< (* 3 az) m) (edge az ax ay s)
              (* m inv-sqrt3))))
 :bounds (fn [o] [o.size o.size o.size])}

;; Cheap octahedron: a bound. The octahedron with vertices :size from the centre on the
;; axes is |x| + |y| + |z| <= s; (|x| + |y| + |z| - s) / sqrt(3) is the distance to the
;; nearest face plane, exact inside and over faces but less than the distance near
;; edges and vertices (up to sqrt(3) times less straight out from a vertex).
(local {: abs} math)

{:kind :cheap-octahedron
 :doc "Octahedron with vertices :size from the centre on the axes (fast bound)."
 :params [{:name :size :type :positive :default 1}]
 :class :bound
 :args [{:name :s :type :float}]
 :pack (fn [o] [o.size])
 :glsl-name "sdCheapOctahedron"
 :glsl "float sdCheapOctahedron(vec3 p, float s) {
    p = abs(p);
    return (p.x + p.y + p.z - s) * 0.5773502691896258;
}"
 :cpu (fn [x y z s]
        (* (- (+ (abs x) (abs y) (abs z)) s) 0.5773502691896258))
 :bounds (fn [o] [o.size o.size o.size])}

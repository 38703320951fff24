;; Dodecahedron: a bound. Regular, :size is the inradius (centre to face). Its twelve
;; face normals are the cyclic permutations of (0, +-1, +-phi) / sqrt(1 + phi^2) (the
;; vertices of an icosahedron), so with p folded by abs three planes remain. The largest
;; face-plane distance: exact inside and over the faces, less beyond edges and vertices.
(local {: max : abs} math)

{:kind :dodecahedron
 :doc "Regular dodecahedron with inradius :size."
 :params [{:name :size :type :positive :default 1}]
 :class :bound
 :args [{:name :r :type :float}]
 :pack (fn [o] [o.size])
 :glsl-name "sdDodecahedron"
 :glsl "float sdDodecahedron(vec3 p, float r) {
    p = abs(p);
    vec2 n = vec2(0.52573111211913359, 0.85065080835203999);
    float a = dot(p.yz, n);
    float b = dot(p.zx, n);
    float c = dot(p.xy, n);
    return max(a, max(b, c)) - r;
}"
 :cpu (fn [x y z r]
        (let [x (abs x) y (abs y) z (abs z)
              u 0.52573111211913359 v 0.85065080835203999]
          (- (max (+ (* u y) (* v z)) (+ (* u z) (* v x)) (+ (* u x) (* v y))) r)))
 ;; The vertices reach sqrt(1 + 1/phi^2) times the inradius along each axis.
 :bounds (fn [o] (let [e (* o.size 1.1755705045849463)] [e e e]))}

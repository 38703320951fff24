;; Dodecahedron: a bound. Regular, :size is the inradius (centre to face). Its twelve
;; face normals are the cyclic permutations of (0, +-1, +-phi) / sqrt(1 + phi^2) (the
;; vertices of an icosahedron), so with p folded by abs three planes remain. The largest
;; face-plane distance: exact inside and over the faces, less beyond edges and vertices.

{:kind :dodecahedron
 :doc "Regular dodecahedron with inradius :size."
 :params [{:name :size :type :positive :default 1}]
 :class :bound
 :args [{:name :r :type :float}]
 :pack (fn [o] [o.size])
 :glsl-name "sdDodecahedron"
 ;; The distance once, in Fennel: src/sdf/translate.fnl writes :glsl and :cpu from it.
 :fennel "(fn [x y z r]
  (let [x (math.abs x) y (math.abs y) z (math.abs z)
        u 0.52573111211913359 v 0.85065080835203999]
    (- (math.max (+ (* u y) (* v z)) (+ (* u z) (* v x)) (+ (* u x) (* v y))) r)))"
 ;; The vertices reach sqrt(1 + 1/phi^2) times the inradius along each axis.
 :bounds (fn [o] (let [e (* o.size 1.1755705045849463)] [e e e]))}

;; Icosahedron: a bound. Regular, :size is the inradius (centre to face). Its twenty
;; face normals point at the vertices of a dodecahedron: (+-1, +-1, +-1) / sqrt(3) and
;; the cyclic permutations of (0, +-phi, +-1/phi) / sqrt(3); with p folded by abs four
;; planes remain. The largest face-plane distance: exact inside and over the faces,
;; less beyond edges and vertices.

{:kind :icosahedron
 :doc "Regular icosahedron with inradius :size."
 :params [{:name :size :type :positive :default 1}]
 :class :bound
 :args [{:name :r :type :float}]
 :pack (fn [o] [o.size])
 :glsl-name "sdIcosahedron"
 ;; The distance once, in Fennel: src/sdf/translate.fnl writes :glsl and :cpu from it.
 :fennel "(fn [x y z r]
  (let [x (math.abs x) y (math.abs y) z (math.abs z)
        u 0.93417235896271578 v 0.35682208977308993]
    (- (math.max (* (+ x y z) 0.57735026918962584)
                 (+ (* u y) (* v z)) (+ (* u z) (* v x)) (+ (* u x) (* v y)))
       r)))"
 ;; The vertices reach sqrt(3)/phi times the inradius along each axis.
 :bounds (fn [o] (let [e (* o.size 1.0704662693192697)] [e e e]))}

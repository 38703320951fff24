;; Cylinder, infinite along z: exact. The distance to the z axis, less the radius.
;; Unbounded, so it has no :bounds.
(local {: sqrt} math)

{:kind :cylinder
 :doc "Infinite cylinder along z of :radius."
 :params [{:name :radius :type :positive :default 0.5}]
 :class :exact
 :args [{:name :r :type :float}]
 :pack (fn [o] [o.radius])
 :glsl-name "sdCylinder"
 :glsl "float sdCylinder(vec3 p, float r) {
    return length(p.xy) - r;
}"
 :cpu (fn [x y z r]
        (- (sqrt (+ (* x x) (* y y))) r))}

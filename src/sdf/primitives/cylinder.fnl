;; Cylinder, infinite along z: exact. The distance to the z axis, less the radius.
;; Unbounded, so it has no :bounds.

{:kind :cylinder
 :doc "Infinite cylinder along z of :radius."
 :params [{:name :radius :type :positive :default 0.5}]
 :class :exact
 :args [{:name :r :type :float}]
 :pack (fn [o] [o.radius])
 :glsl-name "sdCylinder"
 ;; The distance once, in Fennel: src/sdf/translate.fnl writes :glsl and :cpu from it.
 :fennel "(fn [x y z r]
  (- (math.sqrt (+ (* x x) (* y y))) r))"}

;; Torus: exact. A ring of :radius in the xy plane (around z), a tube of :thickness
;; (the tube's radius): the distance to the ring circle, less the tube radius.

{:kind :torus
 :doc "Torus around the z axis: ring :radius, tube radius :thickness."
 :params [{:name :radius :type :positive :default 1}
          {:name :thickness :type :positive :default 0.25}]
 :class :exact
 ;; The same at -v as at v in each coordinate (see :symmetric in src/sdf/primitives.fnl).
 :symmetric [true true true]
 :args [{:name :r :type :float} {:name :t :type :float}]
 :pack (fn [o] [o.radius o.thickness])
 :glsl-name "sdTorus"
 ;; The distance once, in Fennel: src/sdf/translate.fnl writes :glsl and :cpu from it.
 :fennel "(fn [x y z r t]
  (let [qx (- (math.sqrt (+ (* x x) (* y y))) r)]
    (- (math.sqrt (+ (* qx qx) (* z z))) t)))"
 :bounds (fn [o] (let [e (+ o.radius o.thickness)] [e e o.thickness]))}

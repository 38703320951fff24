;; Link (a chain link): exact. A torus in the xy plane cut across and pulled apart along
;; y by :length: the distance to its centre line (two half circles of :radius joined by
;; two straight pieces of :length), less the tube radius :thickness.

{:kind :link
 :doc "Chain link in the xy plane, long along y: straight :length, ring :radius, tube radius :thickness."
 :params [{:name :length :type :length0 :default 0.5}
          {:name :radius :type :positive :default 0.4}
          {:name :thickness :type :positive :default 0.12}]
 :check (fn [o]
          (when (>= o.thickness o.radius)
            (values :thickness (string.format "must be less than :radius (%g)" o.radius))))
 :class :exact
 :args [{:name :le :type :float} {:name :r1 :type :float} {:name :r2 :type :float}]
 :pack (fn [o] [(* o.length 0.5) o.radius o.thickness])
 :glsl-name "sdLink"
 ;; The distance once, in Fennel: src/sdf/translate.fnl writes :glsl and :cpu from it.
 :fennel "(fn [x y z le r1 r2]
  (let [qy (math.max (- (math.abs y) le) 0)
        d (- (math.sqrt (+ (* x x) (* qy qy))) r1)]
    (- (math.sqrt (+ (* d d) (* z z))) r2)))"
 :bounds (fn [o]
           (let [e (+ o.radius o.thickness)]
             [e (+ (* o.length 0.5) e) o.thickness]))}

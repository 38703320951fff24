;; Link (a chain link): exact. A torus in the xy plane cut across and pulled apart along
;; y by :length: the distance to its centre line (two half circles of :radius joined by
;; two straight pieces of :length), less the tube radius :thickness.
(local {: sqrt : max : abs} math)

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
 :glsl "float sdLink(vec3 p, float le, float r1, float r2) {
    vec2 q = vec2(p.x, max(abs(p.y) - le, 0.0));
    return length(vec2(length(q) - r1, p.z)) - r2;
}"
 :cpu (fn [x y z le r1 r2]
        (let [qy (max (- (abs y) le) 0)
              d (- (sqrt (+ (* x x) (* qy qy))) r1)]
          (- (sqrt (+ (* d d) (* z z))) r2)))
 :bounds (fn [o]
           (let [e (+ o.radius o.thickness)]
             [e (+ (* o.length 0.5) e) o.thickness]))}

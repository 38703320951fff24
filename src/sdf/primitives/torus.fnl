;; Torus: exact. A ring of :radius in the xy plane (around z), a tube of :thickness
;; (the tube's radius): the distance to the ring circle, less the tube radius.
(local {: sqrt} math)

{:kind :torus
 :doc "Torus around the z axis: ring :radius, tube radius :thickness."
 :params [{:name :radius :type :positive :default 1}
          {:name :thickness :type :positive :default 0.25}]
 :class :exact
 :args [{:name :r :type :float} {:name :t :type :float}]
 :pack (fn [o] [o.radius o.thickness])
 :glsl-name "sdTorus"
 :glsl "float sdTorus(vec3 p, float r, float t) {
    vec2 q = vec2(length(p.xy) - r, p.z);
    return length(q) - t;
}"
 :cpu (fn [x y z r t]
        (let [qx (- (sqrt (+ (* x x) (* y y))) r)]
          (- (sqrt (+ (* qx qx) (* z z))) t)))
 :bounds (fn [o] (let [e (+ o.radius o.thickness)] [e e o.thickness]))}

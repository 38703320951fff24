;; Sphere: exact. The distance to a point, less the radius.
{:kind :sphere
 :doc "Sphere of :radius."
 :params [{:name :radius :type :positive :default 1}]
 :class :exact
 :args [{:name :r :type :float}]
 :pack (fn [o] [o.radius])
 :glsl-name "sdSphere"
 :glsl "float sdSphere(vec3 p, float r) {
    return length(p) - r;
}"
 :cpu (fn [x y z r]
        (- (math.sqrt (+ (* x x) (* y y) (* z z))) r))
 :bounds (fn [o] [o.radius o.radius o.radius])}

;; Sphere: exact. The distance to a point, less the radius.
{:kind :sphere
 :doc "Sphere of :radius."
 :params [{:name :radius :type :positive :default 1}]
 :class :exact
 ;; Even in each coordinate and never decreasing as its size grows (see :even in
 ;; src/sdf/primitives.fnl): a centred copy in a repetition is the nearest one.
 :even [true true true]
 :args [{:name :r :type :float}]
 :pack (fn [o] [o.radius])
 :glsl-name "sdSphere"
 ;; The distance once, in Fennel: src/sdf/translate.fnl writes :glsl and :cpu from it.
 :fennel "(fn [x y z r]
  (- (math.sqrt (+ (* x x) (* y y) (* z z))) r))"
 ;; The exact normal: the distance's gradient, away from the centre (up at it).
 :gradient-glsl "vec3 gradSphere(vec3 p, float r) {
    float len = length(p);
    return len > 0.0 ? p / len : vec3(0.0, 0.0, 1.0);
}"
 :gradient (fn [x y z _r]
             (let [len (math.sqrt (+ (* x x) (* y y) (* z z)))]
               (if (> len 0) (values (/ x len) (/ y len) (/ z len)) (values 0 0 1))))
 :bounds (fn [o] [o.radius o.radius o.radius])
 ;; A tighter bounding sphere than the box's (see src/render/bounds.fnl).
 :bounding-radius (fn [o] o.radius)}

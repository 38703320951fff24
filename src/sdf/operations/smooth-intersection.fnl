;; The smooth-intersection operation (combine): its descriptor, as src/sdf/operations.fnl lists
;; the fields.

(local {: min : max} math)
(local {: bound-class} (require :src.sdf.operation-kit))

{:kind :smooth-intersection :role :combine
 :class-doc "bound"
 :doc "Intersection blended over :radius (polynomial kernel)."
 :params [{:name :radius :type :positive :default 0.25}]
 :children [2]
 :args [{:name :r :type :float}] :pack (fn [o] [o.radius])
 :glsl-name "opSmoothIntersection"
 :glsl "float opSmoothIntersection(float a, float b, float r) {
    float h = clamp(0.5 - 0.5 * (b - a) / r, 0.0, 1.0);
    return mix(b, a, h) + r * h * (1.0 - h);
}
float wSmoothIntersection(float a, float b, float r) {
    return clamp(0.5 - 0.5 * (b - a) / r, 0.0, 1.0);
}"
 :cpu (fn [a b r]
        (let [h (max 0 (min 1 (- 0.5 (/ (* 0.5 (- b a)) r))))]
          (+ (+ b (* (- a b) h)) (* r h (- 1 h)))))
 :cpu-weight (fn [a b r] (max 0 (min 1 (- 0.5 (/ (* 0.5 (- b a)) r)))))
 :class-of bound-class
 :bounds-of (fn [_ children] (. children 1 :bounds))
 ;; Nodes the tests check it on (test/operations_spec.fnl): its promises on each,
 ;; sampled within :extent (half extents about the origin).
 :examples [{:name "smooth-intersection" :extent [1.5 1.5 1.5]
             :node "{:kind :smooth-intersection :radius 0.3 :children [{:kind :sphere :radius 1} {:kind :box :size [1.5 1.5 1.5]}]}"}]}

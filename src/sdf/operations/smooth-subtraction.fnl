;; The smooth-subtraction operation (combine): its descriptor, as src/sdf/operations.fnl lists
;; the fields.

(local {: min : max} math)
(local {: bound-class : first-bounds} (require :src.sdf.operation-kit))

{:kind :smooth-subtraction :role :combine
 :class-doc "bound"
 :doc "Subtraction blended over :radius (polynomial kernel); the cut shows the cutter's material."
 :params [{:name :radius :type :positive :default 0.25}]
 :children [2]
 :args [{:name :r :type :float}] :pack (fn [o] [o.radius])
 :glsl-name "opSmoothSubtraction"
 :glsl "float opSmoothSubtraction(float a, float b, float r) {
    float h = clamp(0.5 - 0.5 * (a + b) / r, 0.0, 1.0);
    return mix(a, -b, h) + r * h * (1.0 - h);
}
float wSmoothSubtraction(float a, float b, float r) {
    return 1.0 - clamp(0.5 - 0.5 * (a + b) / r, 0.0, 1.0);
}"
 :cpu (fn [a b r]
        (let [h (max 0 (min 1 (- 0.5 (/ (* 0.5 (+ a b)) r))))]
          (+ (+ a (* (- (- b) a) h)) (* r h (- 1 h)))))
 :cpu-weight (fn [a b r] (- 1 (max 0 (min 1 (- 0.5 (/ (* 0.5 (+ a b)) r))))))
 :class-of bound-class
 :bounds-of first-bounds
 ;; Nodes the tests check it on (test/operations_spec.fnl): its promises on each,
 ;; sampled within :extent (half extents about the origin).
 :examples [{:name "smooth-subtraction" :extent [1.5 1.5 1.5]
             :node "{:kind :smooth-subtraction :radius 0.3 :children [{:kind :box :size [2 2 2]} {:kind :sphere :radius 1.2}]}"}]}

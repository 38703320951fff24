;; The smooth-union operation (combine): its descriptor, as src/sdf/operations.fnl lists
;; the fields.

(local {: min : max : log : exp} math)
(local {: bound-class : merge-bounds : grow-bounds} (require :src.sdf.operation-kit))

{:kind :smooth-union :role :combine
 :class-doc "bound"
 :doc "Union blended over :radius (distance units); :kernel :poly (quadratic) or :exp; materials blend by the same weight."
 :params [{:name :radius :type :positive :default 0.25}
          {:name :kernel :type :choice :choices [:poly :exp] :default :poly :structural? true}]
 :children [2]
 :args [{:name :r :type :float}] :pack (fn [o] [o.radius])
 :variants {:poly {:glsl-name "opSmoothUnion"
                   :glsl "float opSmoothUnion(float a, float b, float r) {
    float h = clamp(0.5 + 0.5 * (b - a) / r, 0.0, 1.0);
    return mix(b, a, h) - r * h * (1.0 - h);
}
float wSmoothUnion(float a, float b, float r) {
    return clamp(0.5 + 0.5 * (b - a) / r, 0.0, 1.0);
}"
                   :cpu (fn [a b r]
                          (let [h (max 0 (min 1 (+ 0.5 (/ (* 0.5 (- b a)) r))))]
                            (- (+ b (* (- a b) h)) (* r h (- 1 h)))))
                   :cpu-weight (fn [a b r] (max 0 (min 1 (+ 0.5 (/ (* 0.5 (- b a)) r)))))}
            :exp {:glsl-name "opSmoothUnionExp"
                  :glsl "float opSmoothUnionExp(float a, float b, float r) {
    float m = min(a, b);
    return m - r * log(exp((m - a) / r) + exp((m - b) / r));
}
float wSmoothUnionExp(float a, float b, float r) {
    float m = min(a, b);
    float ea = exp((m - a) / r);
    return ea / (ea + exp((m - b) / r));
}"
                  :cpu (fn [a b r]
                         (let [m (min a b)]
                           (- m (* r (log (+ (exp (/ (- m a) r)) (exp (/ (- m b) r))))))))
                  :cpu-weight (fn [a b r]
                                (let [m (min a b) ea (exp (/ (- m a) r))]
                                  (/ ea (+ ea (exp (/ (- m b) r))))))}}
 :class-of bound-class
 :bounds-of (fn [o children] (grow-bounds (merge-bounds o children) o.radius))
 ;; Nodes the tests check it on (test/operations_spec.fnl): its promises on each,
 ;; sampled within :extent (half extents about the origin).
 :examples [{:name "smooth-union" :extent [2.5 1.5 1.5]
             :node "{:kind :smooth-union :radius 0.5 :children [{:kind :sphere :radius 1 :pos [-0.8 0 0]} {:kind :sphere :radius 1 :pos [0.8 0 0]}]}"}
            {:name "smooth-union-exp" :extent [2.5 1.5 1.5]
             :node "{:kind :smooth-union :kernel :exp :radius 0.2 :children [{:kind :sphere :radius 1 :pos [-0.8 0 0]} {:kind :sphere :radius 1 :pos [0.8 0 0]}]}"}]}

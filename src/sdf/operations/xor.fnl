;; The xor operation (combine): its descriptor, as src/sdf/operations.fnl lists
;; the fields.

(local {: min : max} math)
(local {: bound-class : merge-bounds} (require :src.sdf.operation-kit))

{:kind :xor :role :combine
 :class-doc "bound"
 :doc "What is inside exactly one of its children (a bound)."
 :params []
 :children [2]
 :args [] :pack (fn [] [])
 :glsl-name "opXor"
 :glsl "float opXor(float a, float b) {
    return max(min(a, b), -max(a, b));
}
float wXor(float a, float b) {
    return min(a, b) >= -max(a, b) ? (a <= b ? 1.0 : 0.0) : (a >= b ? 1.0 : 0.0);
}"
 :cpu (fn [a b] (max (min a b) (- (max a b))))
 :cpu-weight (fn [a b] (if (>= (min a b) (- (max a b)))
                           (if (<= a b) 1 0)
                           (if (>= a b) 1 0)))
 :class-of bound-class
 :bounds-of merge-bounds
 ;; Nodes the tests check it on (test/operations_spec.fnl): its promises on each,
 ;; sampled within :extent (half extents about the origin).
 :examples [{:name "xor" :extent [2.5 1.5 1.5]
             :node "{:kind :xor :children [{:kind :sphere :radius 1} {:kind :sphere :radius 1 :pos [1 0 0]}]}"}]}

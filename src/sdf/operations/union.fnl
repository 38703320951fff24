;; The union operation (combine): its descriptor, as src/sdf/operations.fnl lists
;; the fields.

(local {: min} math)
(local {: all-exact : merge-bounds} (require :src.sdf.operation-kit))

{:kind :union :role :combine
 :class-doc "exact when the children are"
 :doc "Union of its children (exact outside when they are)."
 :params []
 :children [1]
 :args [] :pack (fn [] [])
 :glsl-name "opUnion"
 :glsl "float opUnion(float a, float b) {
    return min(a, b);
}
float wUnion(float a, float b) {
    return a <= b ? 1.0 : 0.0;
}"
 :cpu (fn [a b] (min a b))
 :cpu-weight (fn [a b] (if (<= a b) 1 0))
 :keeps-even true
 :class-of all-exact
 :bounds-of merge-bounds
 ;; Nodes the tests check it on (test/operations_spec.fnl): its promises on each,
 ;; sampled within :extent (half extents about the origin).
 :examples [{:name "union" :extent [3.5 3 2]
             :node "{:kind :union :children [{:kind :sphere :radius 1 :pos [-2 0 0]} {:kind :box :size [1 1 1] :pos [2 0 0]} {:kind :sphere :radius 0.5 :pos [0 2 0]}]}"}]}

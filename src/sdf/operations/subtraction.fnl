;; The subtraction operation (combine): its descriptor, as src/sdf/operations.fnl lists
;; the fields.

(local {: max} math)
(local {: bound-class : first-bounds} (require :src.sdf.operation-kit))

{:kind :subtraction :role :combine
 :class-doc "bound"
 :doc "Its first child with the others cut away; the cut shows the cutter's material (a bound)."
 :params []
 :children [2]
 :args [] :pack (fn [] [])
 :glsl-name "opSubtraction"
 :glsl "float opSubtraction(float a, float b) {
    return max(a, -b);
}
float wSubtraction(float a, float b) {
    return a >= -b ? 1.0 : 0.0;
}"
 :cpu (fn [a b] (max a (- b)))
 :cpu-weight (fn [a b] (if (>= a (- b)) 1 0))
 :class-of bound-class
 :bounds-of first-bounds
 ;; Nodes the tests check it on (test/operations_spec.fnl): its promises on each,
 ;; sampled within :extent (half extents about the origin).
 :examples [{:name "subtraction" :extent [1.5 1.5 1.5]
             :node "{:kind :subtraction :children [{:kind :box :size [2 2 2]} {:kind :sphere :radius 1.2} {:kind :sphere :radius 0.5 :pos [1 1 1]}]}"}]}

;; The intersection operation (combine): its descriptor, as src/sdf/operations.fnl lists
;; the fields.

(local {: min : max} math)
(local {: bound-class} (require :src.sdf.operation-kit))

{:kind :intersection :role :combine
 :class-doc "bound"
 :doc "Intersection of its children (a bound)."
 :params []
 :children [2]
 :args [] :pack (fn [] [])
 :glsl-name "opIntersection"
 :glsl "float opIntersection(float a, float b) {
    return max(a, b);
}
float wIntersection(float a, float b) {
    return a >= b ? 1.0 : 0.0;
}"
 :cpu (fn [a b] (max a b))
 :cpu-weight (fn [a b] (if (>= a b) 1 0))
 :keeps-even true
 :class-of bound-class
 :bounds-of (fn [_ children]
              (var out nil)
              (each [_ c (ipairs children)]
                (when c.bounds
                  (set out (if out (icollect [i v (ipairs out)] (min v (. c.bounds i)))
                               c.bounds))))
              out)
 ;; Nodes the tests check it on (test/operations_spec.fnl): its promises on each,
 ;; sampled within :extent (half extents about the origin).
 :examples [{:name "intersection" :extent [1.5 1.5 1.5]
             :node "{:kind :intersection :children [{:kind :sphere :radius 1} {:kind :box :size [1.5 1.5 1.5]}]}"}]}

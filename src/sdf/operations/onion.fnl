;; The onion operation (distance): its descriptor, as src/sdf/operations.fnl lists
;; the fields.

(local {: abs} math)
(local {: first-class : grow-bounds} (require :src.sdf.operation-kit))

{:kind :onion :role :distance
 :class-doc "keeps"
 :doc "Hollows its child into a shell of :thickness (nest onions for layers)."
 :params [{:name :thickness :type :positive :default 0.05}]
 :children [1 1]
 :args [{:name :t :type :float}] :pack (fn [o] [o.thickness])
 :glsl-name "opOnion"
 :glsl "float opOnion(float d, vec3 p, float t) {
    return abs(d) - t;
}"
 :cpu (fn [d _ _ _ t] (- (abs d) t))
 :keeps-symmetric true
 :class-of first-class
 :bounds-of (fn [o children] (grow-bounds (. children 1 :bounds) o.thickness))
 ;; Nodes the tests check it on (test/operations_spec.fnl): its promises on each,
 ;; sampled within :extent (half extents about the origin).
 :examples [{:name "onion" :extent [2 2 2]
             :node "{:kind :onion :thickness 0.1 :children [{:kind :onion :thickness 0.2 :children [{:kind :sphere :radius 1}]}]}"}]}

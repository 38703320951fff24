;; The round operation (distance): its descriptor, as src/sdf/operations.fnl lists
;; the fields.

(local {: first-class : grow-bounds} (require :src.sdf.operation-kit))

{:kind :round :role :distance
 :class-doc "keeps"
 :doc "Rounds its child: grows it by :radius."
 :params [{:name :radius :type :positive :default 0.1}]
 :children [1 1]
 :args [{:name :r :type :float}] :pack (fn [o] [o.radius])
 :glsl-name "opRound"
 :glsl "float opRound(float d, vec3 p, float r) {
    return d - r;
}"
 :cpu (fn [d _ _ _ r] (- d r))
 :keeps-even true
 :class-of first-class
 :bounds-of (fn [o children] (grow-bounds (. children 1 :bounds) o.radius))
 ;; Nodes the tests check it on (test/operations_spec.fnl): its promises on each,
 ;; sampled within :extent (half extents about the origin).
 :examples [{:name "round" :extent [1.5 1.5 1.5]
             :node "{:kind :round :radius 0.2 :children [{:kind :box :size [1 1 1]}]}"}]}

;; The chamfer-union operation (combine): its descriptor, as src/sdf/operations.fnl lists
;; the fields.

(local {: sqrt : min} math)
(local {: bound-class : merge-bounds : grow-bounds} (require :src.sdf.operation-kit))

{:kind :chamfer-union :role :combine
 :class-doc "bound"
 :doc "Union with a 45-degree chamfer of :radius where the children meet."
 :params [{:name :radius :type :positive :default 0.25}]
 :children [2]
 :args [{:name :r :type :float}] :pack (fn [o] [o.radius])
 :glsl-name "opChamferUnion"
 :glsl "float opChamferUnion(float a, float b, float r) {
    return min(min(a, b), (a + b - r) * 0.5);
}
float wChamferUnion(float a, float b, float r) {
    return a <= b ? 1.0 : 0.0;
}"
 ;; The chamfer face is a + b = r. Scaled by 1/sqrt 2 its value is the distance to
 ;; that face where the two gradients are orthogonal, but where they are parallel
 ;; it changes sqrt 2 per unit and overshoots; scaled by 1/2 it never does.
 :cpu (fn [a b r] (min (min a b) (* (- (+ a b) r) 0.5)))
 :cpu-weight (fn [a b] (if (<= a b) 1 0))
 :class-of bound-class
 :bounds-of (fn [o children] (grow-bounds (merge-bounds o children) o.radius))
 ;; Nodes the tests check it on (test/operations_spec.fnl): its promises on each,
 ;; sampled within :extent (half extents about the origin).
 :examples [{:name "chamfer-union" :extent [2 2 3]
             :node "{:kind :chamfer-union :radius 0.4 :children [{:kind :box :size [3 3 1]} {:kind :box :size [1 1 3] :pos [0 0 1]}]}"}]}

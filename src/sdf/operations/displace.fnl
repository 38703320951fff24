;; The displace operation (distance): its descriptor, as src/sdf/operations.fnl lists
;; the fields.

(local {: sqrt : sin} math)
(local {: bound-class : grow-bounds} (require :src.sdf.operation-kit))

{:kind :displace :role :distance
 :class-doc "bound, Lipschitz 1 + a f sqrt 3"
 :doc "Adds :amplitude * sin(fx) sin(fy) sin(fz) with :frequency f to its child's distance (Lipschitz factor 1 + a f sqrt 3)."
 :params [{:name :amplitude :type :positive :default 0.05}
          {:name :frequency :type :positive :default 10}]
 :children [1 1]
 :args [{:name :a :type :float} {:name :f :type :float}]
 :pack (fn [o] [o.amplitude o.frequency])
 :glsl-name "opDisplace"
 :glsl "float opDisplace(float d, vec3 p, float a, float f) {
    return d + a * sin(f * p.x) * sin(f * p.y) * sin(f * p.z);
}"
 :cpu (fn [d x y z a f] (+ d (* a (sin (* f x)) (sin (* f y)) (sin (* f z)))))
 :lipschitz-of (fn [o] (+ 1 (* o.amplitude o.frequency (sqrt 3))))
 :class-of bound-class
 :bounds-of (fn [o children] (grow-bounds (. children 1 :bounds) o.amplitude))
 ;; Nodes the tests check it on (test/operations_spec.fnl): its promises on each,
 ;; sampled within :extent (half extents about the origin).
 :examples [{:name "displace" :extent [2 2 2]
             :node "{:kind :displace :amplitude 0.1 :frequency 5 :children [{:kind :sphere :radius 1}]}"}]}

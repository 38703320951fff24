;; The elongate operation (point): its descriptor, as src/sdf/operations.fnl lists
;; the fields.

(local {: min : max} math)
(local {: first-class} (require :src.sdf.operation-kit))

{:kind :elongate :role :point
 :class-doc "keeps"
 :doc "Stretches its child by inserting :size (full extents) of straight extrusion at its centre."
 :params [{:name :size :type :lengths3 :default [1 0 0]}]
 :children [1 1]
 :args [{:name :h :type :vec3}]
 :pack (fn [o] (icollect [_ v (ipairs o.size)] (* 0.5 v)))
 :glsl-name "opElongate"
 :glsl "vec3 opElongate(vec3 p, vec3 h) {
    return p - clamp(p, -h, h);
}"
 :cpu (fn [x y z hx hy hz]
        (values (- x (max (- hx) (min hx x))) (- y (max (- hy) (min hy y)))
                (- z (max (- hz) (min hz z)))))
 :keeps-symmetric true
 ;; Exact outside; inside the inserted part the distance is 0 or the child's.
 :class-of first-class
 :bounds-of (fn [o children]
              (let [b (. children 1 :bounds)]
                (when b (icollect [i v (ipairs b)] (+ v (* 0.5 (. o.size i)))))))
 ;; Nodes the tests check it on (test/operations_spec.fnl): its promises on each,
 ;; sampled within :extent (half extents about the origin).
 :examples [{:name "elongate" :extent [3 2 2]
             :node "{:kind :elongate :size [2 0 0] :children [{:kind :sphere :radius 1}]}"}]}

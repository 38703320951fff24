;; The translate operation (point): its descriptor, as src/sdf/operations.fnl lists
;; the fields.

(local {: abs} math)
(local {: first-class} (require :src.sdf.operation-kit))

{:kind :translate :role :point
 :class-doc "keeps"
 :doc "Moves its child by :offset."
 :params [{:name :offset :type :vec3 :default [0 0 0]}]
 :children [1 1]
 :args [{:name :t :type :vec3}] :pack (fn [o] o.offset)
 :glsl-name "opTranslate"
 :glsl "vec3 opTranslate(vec3 p, vec3 t) {
    return p - t;
}"
 :cpu (fn [x y z tx ty tz] (values (- x tx) (- y ty) (- z tz)))
 :keeps-even (fn [o axis] (= 0 (. o.offset axis)))
 :class-of first-class
 :bounds-of (fn [o children]
              (let [b (. children 1 :bounds)]
                (when b (icollect [i v (ipairs b)] (+ v (abs (. o.offset i)))))))
 ;; The symmetric bounds above hold the moved child about the old origin; its box
 ;; ({:lo :hi}, see src/sdf/lower.fnl) moves with it.
 :box-of (fn [o [child]]
           {:lo (icollect [i v (ipairs child.lo)] (+ v (. o.offset i)))
            :hi (icollect [i v (ipairs child.hi)] (+ v (. o.offset i)))})
 ;; Nodes the tests check it on (test/operations_spec.fnl): its promises on each,
 ;; sampled within :extent (half extents about the origin).
 :examples [{:name "translate" :extent [2.5 3.5 4.5]
             :node "{:kind :translate :offset [1 2 3] :children [{:kind :sphere :radius 1}]}"}]}

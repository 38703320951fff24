;; The scale operation (point): its descriptor, as src/sdf/operations.fnl lists
;; the fields.

(local {: first-class} (require :src.sdf.operation-kit))

{:kind :scale :role :point
 :class-doc "keeps"
 :doc "Scales its child uniformly by :factor (the distance is scaled back: stays exact)."
 :params [{:name :factor :type :positive :default 1}]
 :children [1 1]
 :args [{:name :s :type :float}] :pack (fn [o] [o.factor])
 :glsl-name "opScale"
 :glsl "vec3 opScale(vec3 p, float s) {
    return p / s;
}"
 :cpu (fn [x y z s] (values (/ x s) (/ y s) (/ z s)))
 :keeps-symmetric true
 :post {:glsl-name "opScaleDistance"
        :glsl "float opScaleDistance(float d, vec3 p, float s) {
    return d * s;
}"
        :cpu (fn [d _ _ _ s] (* d s))}
 :class-of first-class
 :bounds-of (fn [o children]
              (let [b (. children 1 :bounds)]
                (when b (icollect [_ v (ipairs b)] (* v o.factor)))))
 ;; Nodes the tests check it on (test/operations_spec.fnl): its promises on each,
 ;; sampled within :extent (half extents about the origin).
 :examples [{:name "scale" :extent [2 3 2]
             :node "{:kind :scale :factor 2 :children [{:kind :box :size [1 2 1]}]}"}]}

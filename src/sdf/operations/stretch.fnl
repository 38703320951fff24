;; The stretch operation (point): its descriptor, as src/sdf/operations.fnl lists
;; the fields.

(local {: min} math)
(local {: bound-class} (require :src.sdf.operation-kit))

{:kind :stretch :role :point
 :class-doc "bound"
 :doc "Scales its child by :factors [x y z], not uniformly (a bound)."
 :params [{:name :factors :type :size3 :default [1 1 1]}]
 :children [1 1]
 :args [{:name :s :type :vec3} {:name :m :type :float}]
 :pack (fn [o] (let [[x y z] o.factors] [x y z (min x y z)]))
 :glsl-name "opStretch"
 :glsl "vec3 opStretch(vec3 p, vec3 s, float m) {
    return p / s;
}"
 :cpu (fn [x y z sx sy sz] (values (/ x sx) (/ y sy) (/ z sz)))
 :keeps-symmetric true
 ;; d(p / s) changes at most 1 / min(s) per unit: times min(s) it is a bound.
 :post {:glsl-name "opStretchDistance"
        :glsl "float opStretchDistance(float d, vec3 p, vec3 s, float m) {
    return d * m;
}"
        :cpu (fn [d _ _ _ _ _ _ m] (* d m))}
 :class-of bound-class
 :bounds-of (fn [o children]
              (let [b (. children 1 :bounds)]
                (when b (icollect [i v (ipairs b)] (* v (. o.factors i))))))
 ;; Nodes the tests check it on (test/operations_spec.fnl): its promises on each,
 ;; sampled within :extent (half extents about the origin).
 :examples [{:name "stretch" :extent [3 2 2]
             :node "{:kind :stretch :factors [2 1 1] :children [{:kind :sphere :radius 1}]}"}]}

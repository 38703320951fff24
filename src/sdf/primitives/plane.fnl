;; Plane: exact signed distance to the plane dot(p, n) = height, solid below it (on the
;; side opposite the normal). The normal is normalised on load.
{:kind :plane
 :doc "Plane with unit :normal (default up) at :height along it; solid on the far side."
 :params [{:name :height :type :number :default 0}
          {:name :normal :type :direction :default [0 0 1]}]
 :class :exact
 :placed? false
 ;; Solid on one side of a plane: a ray meets it in closed form, distance over the
 ;; gradient's rate (src/render/bounds.fnl's planes).
 :half-space? true
 :args [{:name :n :type :vec3} {:name :h :type :float}]
 :pack (fn [o] (let [[x y z] o.normal] [x y z o.height]))
 :glsl-name "sdPlane"
 :glsl "float sdPlane(vec3 p, vec3 n, float h) {
    return dot(p, n) - h;
}"
 :cpu (fn [x y z nx ny nz h]
        (- (+ (* x nx) (* y ny) (* z nz)) h))
 ;; The exact normal: the plane's own.
 :gradient-glsl "vec3 gradPlane(vec3 p, vec3 n, float h) {
    return n;
}"
 :gradient (fn [_x _y _z nx ny nz _h] (values nx ny nz))}

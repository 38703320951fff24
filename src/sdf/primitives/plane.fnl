;; Plane: exact signed distance to the plane dot(p, n) = height, solid below it (on the
;; side opposite the normal). The normal is normalised on load.

;; A plane facing straight up (the article's ground, every flat :plane) lowers to this
;; form: the normal is known, so the distance is one subtraction, not a dot product
;; with a normal read from the uniforms in every step. Its row is a plane's (normal,
;; height), so taking the camera off (lower.fnl's hand-in) is the same. Another normal
;; is another form: a change of structure, as a kind's.
(local ground
  {:kind :ground
   :doc "A :plane whose normal is +z."
   :params []
   :class :exact
   :lipschitz 1
   :placed? false
   :half-space? true
   :args [{:name :nh :type :vec4}]
   :arg-size 4
   :pack (fn [o] [0 0 1 o.height])
   :glsl-name "sdGround"
   ;; The distance once, in Fennel: src/sdf/translate.fnl writes :glsl and :cpu from it
   ;; (the plane lists this form in its :variants).
   :fennel "(fn [_ _ z _ _ _ h]
  (- z h))"
   :gradient-glsl "vec3 gradGround(vec3 p, vec4 nh) {
    return vec3(0.0, 0.0, 1.0);
}"
   :gradient (fn [] (values 0 0 1))})

{:kind :plane
 :doc "Plane with unit :normal (default up) at :height along it; solid on the far side."
 :params [{:name :height :type :number :default 0}
          {:name :normal :type :direction :default [0 0 1]}]
 :class :exact
 :placed? false
 ;; Solid on one side of a plane: a ray meets it in closed form, distance over the
 ;; gradient's rate (src/render/bounds.fnl's planes).
 :half-space? true
 ;; Facing straight up: the ground form above.
 :variant (fn [o] (let [[x y z] o.normal] (when (and (= x 0) (= y 0) (= z 1)) ground)))
 :variants [ground]
 :args [{:name :n :type :vec3} {:name :h :type :float}]
 :pack (fn [o] (let [[x y z] o.normal] [x y z o.height]))
 :glsl-name "sdPlane"
 ;; The distance once, in Fennel: src/sdf/translate.fnl writes :glsl and :cpu from it.
 :fennel "(fn [x y z nx ny nz h]
  (- (+ (* x nx) (* y ny) (* z nz)) h))"
 ;; The exact normal: the plane's own.
 :gradient-glsl "vec3 gradPlane(vec3 p, vec3 n, float h) {
    return n;
}"
 :gradient (fn [_x _y _z nx ny nz _h] (values nx ny nz))}

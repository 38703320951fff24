;; The large sphere: how lowering draws a sphere of radius 1000 or more (a planet). Its
;; usual form, length(p - c) - r, loses everything near the surface in float32: the
;; spacing at 1e6 is 0.06, while shadow and mirror rays start a few micro-units off it.
;; This form is exact and free of cancellation: (|u|^2 - r^2) / (|u| + r) with
;; u = p - c, expanded as |p|^2 - 2 p.c + k, where k = |c|^2 - r^2 for the
;; camera-relative centre c comes from the CPU in double, as (|c| - r)(|c| + r).
;; A descriptor like src/sdf/primitives/' (but no scene file names it): lowering
;; (src/sdf/lower.fnl) picks it for a placed sphere, the tape's :derived rows say where
;; k goes, and src/render/uniforms.fnl fills them with `k` below.

(local sphere (require :src.sdf.primitives.sphere))

;; From this radius on a sphere is drawn so.
(local radius 1000)

(fn k [[x y z] r [cx cy cz]]
  "|c|^2 - r^2 for the centre (x y z) made relative to the camera at (cx cy cz), in
double and without cancellation: the camera's height above the surface times a large
number."
  (let [dx (- x cx) dy (- y cy) dz (- z cz)
        len (math.sqrt (+ (* dx dx) (* dy dy) (* dz dz)))]
    (* (- len r) (+ len r))))

(local descriptor
  {:kind :large-sphere
   :doc "A :sphere of radius 1000 or more, lowered to a cancellation-free distance."
   :class :exact
   :lipschitz 1
   ;; s: the centre (a camera-relative row) and the radius; k: see above.
   :args [{:name :s :type :vec4} {:name :k :type :float}]
   :arg-size 5
   :glsl-name "sdLargeSphere"
   :glsl "float sdLargeSphere(vec3 p, vec4 s, float k) {
    return (dot(p, p) - 2.0 * dot(p, s.xyz) + k) / (length(p - s.xyz) + s.w);
}"
   ;; On the CPU, in double and world coordinates, the plain sphere is exact.
   :cpu (fn [x y z cx cy cz r _k] (sphere.cpu (- x cx) (- y cy) (- z cz) r))
   ;; A direction needs no cancellation-free form: the sphere's own gradient.
   :gradient-glsl "vec3 gradLargeSphere(vec3 p, vec4 s, float k) {
    return gradSphere(p - s.xyz, s.w);
}"
   :gradient-needs "gradSphere"
   :gradient (fn [x y z cx cy cz r _k] (sphere.gradient (- x cx) (- y cy) (- z cz) r))})

(fn large? [node]
  "Whether the sphere node `node` is drawn as a large sphere."
  (and (= node.kind :sphere) (>= node.radius radius)))

{: descriptor : k : radius : large?}

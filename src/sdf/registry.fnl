;; The kind-grouped path: the first version's flat spheres, boxes and planes, drawn from
;; per-kind uniform arrays (one loop or unrolled block per kind) rather than the tape.
;; Each entry holds the kind's parameters as scene files write them, its uniform layout,
;; and how it calls its primitive descriptor (src/sdf/primitives/) with the position
;; applied: the GLSL function and the CPU form are the descriptor's, described once.
;; :gradient-glsl and :gradient call the descriptor's exact normal the same way
;; (:gradient-of names the descriptor when the entry draws with a chunk of its own).

(local sqrt math.sqrt)
(local abs math.abs)
(local max math.max)
(local min math.min)

(local primitives (require :src.sdf.primitives))

(local sphere-cpu (. (primitives.lookup :sphere) :cpu))
(local box-cpu (. (primitives.lookup :box) :cpu))
(local plane-cpu (. (primitives.lookup :plane) :cpu))
(local sphere-gradient (. (primitives.lookup :sphere) :gradient))
(local box-gradient (. (primitives.lookup :box) :gradient))

(fn sphere-distance [o x y z]
  "Distance from (x y z) to sphere `o` (world coordinates, double)."
  (let [[cx cy cz] o.pos]
    (sphere-cpu (- x cx) (- y cy) (- z cz) o.radius)))

(fn box-distance [o x y z]
  "Signed distance from (x y z) to the axis-aligned box `o`."
  (let [[cx cy cz] o.pos
        [sx sy sz] o.size]
    (box-cpu (- x cx) (- y cy) (- z cz) (* sx 0.5) (* sy 0.5) (* sz 0.5))))

(fn plane-distance [o x y z]
  "Signed distance from (x y z) to the ground plane z = o.height."
  (plane-cpu x y z 0 0 1 o.height))

;; Exact normals, the distances' gradients (the descriptors' :gradient).

(fn sphere-normal [o x y z]
  (let [[cx cy cz] o.pos]
    (sphere-gradient (- x cx) (- y cy) (- z cz) o.radius)))

(fn box-normal [o x y z]
  (let [[cx cy cz] o.pos
        [sx sy sz] o.size]
    (box-gradient (- x cx) (- y cy) (- z cz) (* sx 0.5) (* sy 0.5) (* sz 0.5))))

(fn plane-normal [] (values 0 0 1))

;;; Uniform packers: each takes the object and the camera position and returns the
;;; values of one array element. Positions are made camera-relative here, in double.

(fn relative [[x y z] [cx cy cz]]
  [(- x cx) (- y cy) (- z cz)])

;; From this radius on a sphere is drawn by its cancellation-free distance: float32
;; spacing at 1e6 is 0.06, so length(p - c) - r loses everything near a planet's
;; surface, while shadow and mirror rays start a few micro-units off it.
(local large-radius 1000)

(fn large-sphere-k [o [cx cy cz]]
  ;; |c|^2 - r^2 for the camera-relative centre c, in double, as (|c| - r)(|c| + r):
  ;; the camera's height above the surface times a large number, no cancellation.
  (let [[x y z] o.pos
        dx (- x cx) dy (- y cy) dz (- z cz)
        len (math.sqrt (+ (* dx dx) (* dy dy) (* dz dz)))]
    (* (- len o.radius) (+ len o.radius))))

(local kinds
  [{:kind :sphere
    :doc "Sphere of :radius around :pos."
    :params [{:name :pos :type :vec3 :default [0 0 0]}
             {:name :radius :type :positive :default 1}
             {:name :color :type :color :default [1 1 1]}]
    :primitive :sphere
    :exact? true
    :uniforms [{:name "uSphere" :type :vec4
                :pack (fn [o cam] (let [[x y z] (relative o.pos cam)] [x y z o.radius]))}
               {:name "uSphereColor" :type :vec3 :pack (fn [o] o.color)}]
    :distance-glsl "sdSphere(p - uSphere[i].xyz, uSphere[i].w)"
    :color-glsl "uSphereColor[i]"
    :distance sphere-distance
    :gradient-glsl "gradSphere(p - uSphere[i].xyz, uSphere[i].w)"
    :gradient sphere-normal
    ;; Lowering: large spheres take the large-sphere code (same CPU distance).
    :variant (fn [o] (when (>= o.radius large-radius) :large-sphere))}
   {:kind :large-sphere
    :internal? true
    :shown-as "sphere of radius 1000 or more"
    :doc "A :sphere of radius 1000 or more, lowered to a cancellation-free distance."
    :params []
    :chunk "shaders/sdf/large-sphere.glsl"
    :exact? true
    :uniforms [{:name "uLargeSphere" :type :vec4
                :pack (fn [o cam] (let [[x y z] (relative o.pos cam)] [x y z o.radius]))}
               {:name "uLargeSphereK" :type :float :pack (fn [o cam] [(large-sphere-k o cam)])}
               {:name "uLargeSphereColor" :type :vec3 :pack (fn [o] o.color)}]
    :distance-glsl "sdLargeSphere(p, uLargeSphere[i], uLargeSphereK[i])"
    :color-glsl "uLargeSphereColor[i]"
    :distance sphere-distance
    ;; A direction needs no cancellation-free form: the sphere's own gradient.
    :gradient-of :sphere
    :gradient-glsl "gradSphere(p - uLargeSphere[i].xyz, uLargeSphere[i].w)"
    :gradient sphere-normal}
   {:kind :box
    :doc "Axis-aligned box with full extents :size centred on :pos."
    :params [{:name :pos :type :vec3 :default [0 0 0]}
             {:name :size :type :size3 :default [1 1 1]}
             {:name :color :type :color :default [1 1 1]}]
    :primitive :box
    :exact? true
    :uniforms [{:name "uBoxCenter" :type :vec3 :pack (fn [o cam] (relative o.pos cam))}
               {:name "uBoxHalfSize" :type :vec3
                :pack (fn [o] (let [[x y z] o.size] [(* x 0.5) (* y 0.5) (* z 0.5)]))}
               {:name "uBoxColor" :type :vec3 :pack (fn [o] o.color)}]
    :distance-glsl "sdBox(p - uBoxCenter[i], uBoxHalfSize[i])"
    :color-glsl "uBoxColor[i]"
    :distance box-distance
    :gradient-glsl "gradBox(p - uBoxCenter[i], uBoxHalfSize[i])"
    :gradient box-normal}
   {:kind :plane
    :doc "Ground plane z = :height, facing up."
    :params [{:name :height :type :number :default 0}
             {:name :color :type :color :default [1 1 1]}]
    :primitive :plane
    :exact? true
    :uniforms [{:name "uPlaneHeight" :type :float
                :pack (fn [o [_ _ cz]] [(- o.height cz)])}
               {:name "uPlaneColor" :type :vec3 :pack (fn [o] o.color)}]
    :distance-glsl "sdPlane(p, vec3(0.0, 0.0, 1.0), uPlaneHeight[i])"
    :color-glsl "uPlaneColor[i]"
    :distance plane-distance
    :gradient-glsl "gradPlane(p, vec3(0.0, 0.0, 1.0), uPlaneHeight[i])"
    :gradient plane-normal}])

(local by-kind (collect [_ entry (ipairs kinds)] entry.kind entry))

(fn lookup [kind]
  "The registry entry for `kind` (a string), or nil. Internal kinds (lowering
variants such as :large-sphere) are found too; scene files cannot name them."
  (. by-kind kind))

(fn kind-names []
  "The kind names a scene file may use, in registry order."
  (icollect [_ entry (ipairs kinds)] (when (not entry.internal?) entry.kind)))

(fn lowered-kind [o]
  "The registry kind that draws object `o`: its own, or a variant of it."
  (let [entry (. by-kind o.kind)]
    (or (and entry.variant (entry.variant o)) o.kind)))

(fn count-uniform [kind]
  "Name of the uber shader's object-count uniform for `kind`: :large-sphere ->
uCountLargeSphere."
  (.. "uCount" (pick-values 1 (: (.. "-" kind) :gsub "%-(%l)" string.upper))))

(fn slots-per-object [entry]
  "Uniform vectors (vec4 slots) one object of this kind takes: every array element
of float, vec3 or vec4 occupies one slot."
  (length entry.uniforms))

{: kinds : lookup : kind-names : lowered-kind : count-uniform : slots-per-object
 : large-radius}

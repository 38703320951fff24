;; The primitive catalogue: one descriptor file per primitive in src/sdf/primitives/,
;; found by listing that folder (adding a primitive is adding one file and its tests).
;; Primitives are centred at the origin, z up; placement, rotation and scale are
;; operations (src/sdf/operations.fnl).
;;
;; A descriptor is a table:
;;   :kind        the name scene files use (keyword)
;;   :doc         one line for `--kinds` and docs/scenes.md
;;   :params      [{:name :type :default ...}] checked by the scene loader (types in
;;                src/scene/load.fnl: :positive :number :vec3 :size3 :direction
;;                :degrees (with :min :max) :fraction :length0 :count)
;;   :check       optional (fn [o]) -> nil, or the parameter name and a reason, for
;;                constraints between parameters (o holds every parameter, defaults in)
;;   :class       :exact (the exact signed distance, at least outside the shape) or
;;                :bound (never more than the distance: safe to march, slower)
;;   :lipschitz   optional, default 1
;;   :even        optional [x y z] booleans: along each true axis the distance is even
;;                (the same at -v as at v) and never decreases as |v| grows, the other
;;                coordinates held (a box, a sphere, a cylinder along z). A repetition
;;                of a centred child like that needs only the point's own cell: every
;;                other copy is farther (see src/sdf/lower.fnl)
;;   :symmetric   optional [x y z] booleans: along each true axis the distance is the
;;                same at -v as at v (:even implies it). A polar repetition of a child
;;                symmetric in y folds the point into its sector by reflections (see
;;                polar-fold in src/sdf/operations.fnl)
;;   :args        [{:name :type}] the arguments of the GLSL function after p, with
;;                GLSL types :float :vec2 :vec3 :vec4
;;   :pack        (fn [o]) -> flat list of numbers for :args, in order
;;   :glsl-name   the GLSL function's name, sdCamelCase
;;   :glsl        the GLSL function's text: float sdX(vec3 p, <args>)
;;   :cpu         (fn [x y z ...args as flat numbers]) -> distance, in double
;;   :fennel      instead of :glsl and :cpu: the distance as the text of a Fennel
;;                (fn [x y z ...args as flat numbers] ...), in the subset of
;;                src/sdf/translate.fnl, which writes both from it
;;   :bounds      optional (fn [o]) -> [hx hy hz] half extents of a box centred at
;;                the origin that holds the shape; absent when it is unbounded
;;   :variant     optional (fn [o]) -> another descriptor for this node, or nil: a form
;;                lowered instead where the parameters allow a cheaper one (the plane's
;;                ground)
;;   :variants    the descriptors :variant may return; their :fennel is translated
;;                as the descriptor's own is
;;   :placed?     false for primitives placed by their own parameters (the plane)
;;   :half-space? true for a primitive solid on one side of a plane (the plane): its
;;                distance over its gradient's rate along a ray gives where the ray
;;                meets it, so bounded marches meet it in closed form
;;   :bounding-radius  optional (fn [o]) -> the radius of a sphere about the origin
;;                that holds the shape, where tighter than the :bounds box's
;;   :gradient-glsl  optional: the exact normal in closed form, the distance's gradient,
;;                `vec3 gradX(vec3 p, <args>)` (X as in sdX), with
;;   :gradient    (fn [x y z ...args]) -> nx ny nz, in double; objects whose kind has
;;                one take it as their normal instead of finite differences

(local fennel (require :fennel))
(local files (require :src.util.files))
(local translate (require :src.sdf.translate))

(local dir "src/sdf/primitives")

(local glsl-types {:float 1 :vec2 2 :vec3 3 :vec4 4})

(fn from-fennel! [d file]
  ;; :glsl and :cpu of a descriptor written as :fennel text, both from its one form.
  (let [(ok? form) ((fennel.parser (fennel.string-stream d.fennel) file))
        (t err line) (translate.translate (assert (and ok? form) (.. file ": :fennel does not parse"))
                                          {:name d.glsl-name :scale? false
                                           :arg-types (icollect [_ a (ipairs d.args)] a.type)})]
    (assert t (.. file ": :fennel, line " (tostring line) " of its text: " (tostring err)))
    (set d.glsl t.glsl)
    (set d.cpu (translate.compile-lua t.lua))))

(fn check-descriptor [d file]
  (fn need [ok? what] (assert ok? (.. file ": descriptor " what)))
  (when (and (= (type d) :table) (= (type d.fennel) :string) (= (type d.args) :table))
    (from-fennel! d file)
    (each [_ v (ipairs (or d.variants []))]
      (when (= (type v.fennel) :string) (from-fennel! v file))))
  (need (= (type d) :table) "must be a table")
  (need (and (= (type d.kind) :string) (d.kind:match "^[a-z][a-z0-9%-]*$")) "needs a :kind name")
  (need (= (type d.doc) :string) "needs :doc")
  (need (= (type d.params) :table) "needs :params")
  (need (or (= d.class :exact) (= d.class :bound)) "needs :class :exact or :bound")
  (need (and (= (type d.args) :table) (= (type d.pack) :function)) "needs :args and :pack")
  (each [_ a (ipairs d.args)]
    (need (. glsl-types a.type) (.. "arg " (tostring a.name) " has an unknown GLSL type")))
  (need (and (= (type d.glsl-name) :string) (= (type d.glsl) :string)
             (d.glsl:find (.. "float " d.glsl-name "(vec3 p") 1 true))
        "needs :glsl defining float <:glsl-name>(vec3 p, ...)")
  (need (= (type d.cpu) :function) "needs :cpu")
  (when (or d.gradient d.gradient-glsl)
    (need (and (= (type d.gradient) :function) (= (type d.gradient-glsl) :string)
               (d.gradient-glsl:find (.. "vec3 " (d.glsl-name:gsub "^sd" "grad") "(vec3 p") 1 true))
          "needs both :gradient and :gradient-glsl defining vec3 grad<Name>(vec3 p, ...)"))
  (set d.lipschitz (or d.lipschitz 1))
  (set d.arg-size (accumulate [n 0 _ a (ipairs d.args)] (+ n (. glsl-types a.type))))
  d)

(fn load-all []
  (let [names (assert (files.list-project dir))
        out []]
    (each [_ name (ipairs names)]
      (let [base (name:match "^(.-)%.fnl$")]
        (when base
          (table.insert out (check-descriptor (require (.. "src.sdf.primitives." base))
                                              (.. dir "/" name))))))
    out))

(local all (load-all))
(local by-kind (collect [_ d (ipairs all)] d.kind d))

(fn lookup [kind]
  "The descriptor of primitive `kind`, or nil."
  (. by-kind kind))

(fn kind-names []
  "The primitive kinds, sorted."
  (icollect [_ d (ipairs all)] d.kind))

{: all : lookup : kind-names : glsl-types}

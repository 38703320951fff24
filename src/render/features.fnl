;; Lighting features of the modern model, each declared once: one descriptor file in
;; src/render/features/ and its chunk, found by listing that folder. The loader takes
;; their settings into the :lighting section, the plan keeps those that are on (and
;; so the key), codegen includes their chunks and fills the modern view's slots with
;; their lines, the uniforms send theirs, and the CPU reference
;; (src/reference/lighting.fnl) adds their terms at the same places.
;;
;; A descriptor:
;;   :name      keyword; :doc one line
;;   :settings  {:field {:type :default}}: fields of a scene's :lighting (types as
;;              src/scene/load.fnl checks them)
;;   :on?       (fn [lighting]) -> whether the scene's checked :lighting uses it
;;   :uniforms  (fn [lighting cam-pos]) -> [{:name :type :values}] (src/render/uniforms.fnl)
;;   :chunk     the GLSL file holding its uniforms' declarations and its functions
;;   :slot      the slot its :lines go into: in the modern view (shaders/views/modern.glsl)
;;              :occlusion (lines that scale `occ`, the sky light's share),
;;              :surface (lines that add to `surface`, the light leaving the point) or
;;              :segment (a path segment: lines that scale `through` and add to
;;              `radiance`); in directLight (shaders/shading/modern/lights.glsl) :light
;;              (each light's: lines that add to `c`, given `radiance` arriving)
;;   :lines     the GLSL lines for that slot
;;   :cpu       (fn [lighting tracer]) -> the slot's term on the CPU, in double:
;;              :occlusion (fn [px py pz nx ny nz]) -> a factor;
;;              :surface (fn [s]) -> r g b to add, s a table of the hit: :p :n :v
;;              (toward the viewer) :albedo (linear) :cos-view :sky (the sky's light
;;              along the normal, linear), and :mirror :roughness;
;;              :light (fn [s lx ly lz lr lg lb]) -> r g b to add, for a light from
;;              direction l whose radiance arrives;
;;              :segment (fn [ox oy oz dx dy dz t]) -> the share that crosses the
;;              segment, and r g b it adds (before the path's weight)
;;   :reach     optional (fn [lighting]) -> how far from a surface its distance
;;              queries look (a field lists objects at least that near each cell)
;;   :taps      optional {:chunk :count}: its distance samples as the first turns of
;;              the first light's soft shadow march, where the scene has one (see
;;              plan.lighting's :taps; one copy of the scene for both): the chunk's
;;              parts fill shaders/shading/modern/shadow-soft.glsl's slots, :count
;;              names the constant of how many, and its :lines are then not used

;; `pairs` under another name: a loop over `pairs` by that name is LuaJIT's ITERN,
;; which Debian 12's LuaJIT ends early once despecialised (see src/util/wire.fnl).
(local each-pair pairs)

(local files (require :src.util.files))

(local dir "src/render/features")

(local slots {:occlusion true :surface true :segment true :light true})

(fn check-descriptor [d file]
  (fn need [ok? what] (assert ok? (.. file ": feature " what)))
  (need (= (type d.name) :string) "needs a :name")
  (need (= (type d.doc) :string) "needs :doc")
  (need (= (type d.settings) :table) "needs :settings")
  (need (= (type d.on?) :function) "needs :on?")
  (need (= (type d.uniforms) :function) "needs :uniforms")
  (need (= (type d.chunk) :string) "needs a :chunk")
  (need (. slots d.slot) "needs a :slot: occlusion, surface, segment or light")
  (need (= (type d.lines) :table) "needs :lines")
  (need (= (type d.cpu) :function) "needs :cpu")
  d)

(local all
  (let [out []]
    (each [_ name (ipairs (assert (files.list-project dir)))]
      (let [base (name:match "^(.-)%.fnl$")]
        (when base
          (table.insert out (check-descriptor (require (.. "src.render.features." base))
                                              (.. dir "/" name))))))
    (table.sort out (fn [a b] (< a.name b.name)))
    out))

(local by-name (collect [_ d (ipairs all)] d.name d))

(fn settings []
  "Every feature's settings, merged: field -> {:type :default}."
  (let [out {}]
    (each [_ d (ipairs all)]
      (each [k v (each-pair d.settings)] (tset out k v)))
    out))

(fn active [lighting]
  "The names of the features `lighting` (a checked :lighting section) has on, in
name order."
  (icollect [_ d (ipairs all)] (when (d.on? lighting) d.name)))

(fn lookup [name]
  "The descriptor of feature `name`."
  (. by-name name))

(fn slot-lines [names slot ?taps]
  "The lines the features `names` put into the modern view's `slot`; none of feature
`?taps`, whose samples the soft shadow march takes (plan.lighting's :taps)."
  (let [out []]
    (each [_ name (ipairs names)]
      (let [d (. by-name name)]
        (when (and (= d.slot slot) (not= name ?taps))
          (each [_ l (ipairs d.lines)] (table.insert out l)))))
    out))

{: all : settings : active : lookup : slot-lines : slots}

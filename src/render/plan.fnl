;; Lowering: a validated scene becomes a plan, the plain-data description of the shader
;; the scene needs (which kinds, how many of each, which features, which view), plus the
;; objects in the order the shader stores them. Equal plans mean the same shader.

;; `pairs` under another name: a loop over `pairs` by that name is LuaJIT's ITERN,
;; which Debian 12's LuaJIT ends early once despecialised (see src/util/wire.fnl).
(local each-pair pairs)

(local lower (require :src.sdf.lower))
(local interpret (require :src.sdf.interpret))
(local bounds (require :src.render.bounds))
(local field (require :src.render.field))
(local emit-glsl (require :src.sdf.emit-glsl))
(local features (require :src.render.features))
(local grid (require :src.sdf.grid))
(local uniforms (require :src.render.uniforms))
(local strategies (require :src.sdf.strategies))

(local views [:shaded :normals :glow :heat])

;; Uniform vectors that are not per-object: the common uniforms, feature switches and
;; what LÖVE adds to every fragment shader, rounded up generously.
(local fixed-uniform-vectors 32)

;; llvmpipe links at most 4096 vec4 of fragment uniforms (measured on Mesa 22.3);
;; love.graphics.validateShader does not catch an overflow, so the plan checks it.
(local default-uniform-limit 4096)

;; Tree nodes the shader may hold written out: every node of an object is straight-line
;; code (an instance group's once, in its loop), and llvmpipe's compile time grows
;; faster than linearly: 200 nodes 0.9 s, 500 nodes 3.6 s, 1900 nodes 59 s (measured).
(local max-written-nodes 500)

;; A custom node's function (src/sdf/translate.fnl) is written once however many
;; objects use it, and counts one node for every `ops-per-node` of its operations per
;; point (loops counted by their turns): 8 distinct functions of about 3,400 compiled
;; in 1.5 s on llvmpipe (counted 432 nodes, under the 500 that take 3.6 s) and 30 of
;; them in 15.5 s (counted 1620: refused).
(local ops-per-node 64)

(fn written-nodes [tape]
  ;; The nodes of the tape's objects as written in the shader: each object's, an
  ;; instance group's once; not the translations lowering adds (:implicit?); each
  ;; custom function once (see ops-per-node). Also the object that writes the most,
  ;; and how many.
  (local functions {})
  (fn count [info]
    ;; A blend (lower.fnl's :blend) writes one child for all.
    (accumulate [n (+ (if info.implicit? 0 1)
                      (case info.custom
                        {: key : cost} (if (. functions key) 0
                                           (do (tset functions key true)
                                               (math.ceil (/ (or cost 0) ops-per-node))))
                        _ 0))
                 i c (ipairs (or info.children []))
                 &until (and info.blend? (> i 1))]
      (+ n (count c))))
  (var (total most most-n) (values 0 nil 0))
  (each [_ o (ipairs tape.objects)]
    (let [n (count o.info)]
      (set total (+ total n))
      (when (> n most-n) (set (most most-n) (values o n)))))
  (values total most most-n))

(fn custom-in? [info]
  (or (not= nil info.custom)
      (accumulate [found? false _ c (ipairs (or info.children []))] (or found? (custom-in? c)))))

(fn nodes-message [scene tape]
  (let [(total most most-n) (written-nodes tape)]
    (string.format "%s: %s: the shader would hold %d tree nodes written out, more than %d (compiling grows faster than their number); this object writes %d of them. %s"
                   scene.file most.info.path total max-written-nodes most-n
                   (if (custom-in? most.info)
                       (.. "A custom function counts one node for every " ops-per-node
                           " of its operations per point, once however many objects use it: write it shorter, or let objects share one function (their numbers in :params)")
                       "Objects of one structure (the same kinds and fields, other numbers) share one loop: make more of them alike, or remove some"))))

;; Adaptive supersampling's edge tests (shaders/pipeline/adaptive.glsl and the
;; reference's needs-samples?): a pixel's footprint further along the centre ray, a
;; whole-scene normal that turns from the surface's own by 1 - cos > edge-turn (an
;; edge, another object), or by more than limb-turn where the view meets the surface
;; at a cosine under `grazing` (the limb of a curved surface). Chosen on gallery,
;; lighting and organic at 640x360: 2.4-6.5% of pixels flagged. And what no test on
;; the centre ray sees (an edge seen in a mirror, a shadow's edge, an object smaller
;; than the pixel, a near miss): a second ray at `second` (x, y in the pixel, 0..1)
;; whose colour's luma differs from the centre's by more than `contrast` (0..1). With
;; it, the 4 x 4 still of every showcase scene has no unsupported firefly at 320x180
;; (contrast 0.06 to 0.15 alike; test/specks_spec.fnl). A centre ray of many steps no
;; longer counts as an edge: in colonnade nearly every ray takes 24 (its tiles and
;; flutes), and the grid there cost 9.2 s at 640x360 on llvmpipe against 5.5 s without
;; that test, for the same pictures' fireflies (none).
(local edge-tests {:grazing 0.3 :edge-turn 0.1 :limb-turn 1e-4
                   :second [0.875 0.875] :contrast 0.1})

(fn view? [v]
  (var found? false)
  (each [_ name (ipairs views)] (when (= name v) (set found? true)))
  found?)

;; The key: equal keys mean the same generated code. It is derived from the plan
;; itself: every field is structure (it decides what the code holds), but these, which
;; travel as uniforms and textures or are counted from the rest. A new field is in the
;; key without anyone listing it: at worst a value edit compiles again, never a
;; stale shader.
(local value-fields {:objects true :reflections true :uniform-vectors true
                     :texels true :key true})

;; Of nested parts, what the code reads: the tape's key (its own structure, derived
;; the same way in lower.fnl), a field's kinds, walk and object count (unless the
;; code reads it from a uniform: the interpreter's, interpret.tape-of).
(local parts {:tape (fn [tape] tape.key)
              ;; Which groups have grids (their sizes travel as uniforms).
              :grids (fn [gs] (icollect [_ e (ipairs gs.list)] (or e.id "blend")))
              :field (fn [fd plan]
                       {:kinds fd.kinds :walk? fd.walk?
                        :count (when (not (?. plan.tape.objects 1 :count-read?)) fd.count)})})

(fn key-text [v]
  ;; A deterministic text of plain data: tables with their keys sorted.
  (if (not= (type v) :table)
      (if (= (type v) :number) (string.format "%.9g" v) (tostring v))
      (let [ks (icollect [k (each-pair v)] k)]
        (table.sort ks (fn [a b] (< (tostring a) (tostring b))))
        (.. "{" (table.concat (icollect [_ k (ipairs ks)] (.. (tostring k) "=" (key-text (. v k)))) " ")
            "}"))))

(fn structure-key [plan]
  (let [ks (icollect [k (each-pair plan)] (when (not (. value-fields k)) k))]
    (table.sort ks)
    (table.concat (icollect [_ k (ipairs ks)]
                    (let [part (. parts k)]
                      (.. k "=" (key-text (if part (part (. plan k) plan) (. plan k))))))
                  " ")))

(fn object-label [o]
  ;; What a tape object draws, for a message: its placed node's kind.
  (let [info (if (and o.info.implicit? (. o.info.children 1)) (. o.info.children 1) o.info)]
    (if o.info.large? "sphere of radius 1000 or more" info.kind)))

(fn budget-message [scene plan limit]
  (let [seen {}
        costs []
        _ (each [_ o (ipairs plan.tape.objects)]
            (let [text (.. "a " (object-label o) " takes " o.size)]
              (when (not (. seen text))
                (tset seen text true)
                (table.insert costs text))))
        over (- plan.uniform-vectors limit)]
    (.. scene.file ": objects: the scene needs " plan.uniform-vectors
        " uniform vectors but the driver allows " limit " (" fixed-uniform-vectors
        " are reserved); remove objects worth " over " vectors ("
        (table.concat costs ", ") ")")))

(local software-renderers ["llvmpipe" "softpipe" "swrast" "swiftshader" "software" "gdi generic"])

(fn software-renderer? [name]
  "Whether the OpenGL renderer called `name` (the fourth value of LÖVE's
getRendererInfo) rasterises on the CPU: Mesa's llvmpipe, softpipe or swrast,
SwiftShader, Microsoft's GDI renderer."
  (let [n (: (tostring name) :lower)]
    (accumulate [found? false _ s (ipairs software-renderers) &until found?]
      (not= nil (n:find s 1 true)))))

(fn software-interpreted [interpreted options scene]
  ;; The interpreter's tape `interpreted`, or nil and why on a software renderer
  ;; (options.software?) where its loops would be cut short: its turns a distance
  ;; times the rays a pixel takes (a still's N x N and two more at most) must fit
  ;; (interpret.software-fits?).
  (let [samples (or options.samples scene.render.samples 1)
        rays (if (> samples 1) (+ (* samples samples) 2) 1)]
    (case (if options.software?
              (interpret.software-fits? (. (interpret.program-object interpreted) :tape) rays)
              true)
      true interpreted
      (false turns most)
      (values nil (string.format (.. "its program takes %d loop turns a distance%s, and llvmpipe stops "
                                     "a shader's loops after 65,535 turns in all: a software renderer "
                                     "draws at most %d turns a distance right (--samples 1 takes one ray "
                                     "a pixel; a GPU has no such limit; without --interpret the scene's "
                                     "own shader draws it)")
                                 turns (if (> rays 1) (string.format " for each of %d rays a pixel" rays) "")
                                 most)))))

(fn renderer-options [name ?options]
  "`?options` for scene->plan with what suits the renderer called `name` filled in
where they leave it open. On a software renderer each uniform is copied once per
pixel (:load-once?): there a uniform read is an eight-lane gather, every time. A
GPU reads uniforms from a constant cache, and there the shader reads them where it
uses them (measured on an H100: colonnade at 1920x1080 in 451 ms against 655 with
the copies, flower 193 against 221, gallery and the seed alike). And :software?, so
the tape interpreter refuses a program too long for a software renderer's loops."
  (let [options (collect [k v (each-pair (or ?options {}))] k v)]
    (when (= nil options.load-once?)
      (set options.load-once? (software-renderer? name)))
    (when (= nil options.software?)
      (set options.software? (software-renderer? name)))
    options))

(fn grids-of [tape]
  "The grids of `tape`'s instance groups (src/sdf/grid.fnl): one for each object whose
strategy's :grid-boxes gives boxes (a group of at least grid.min-members members that
all have a box: finite, not a half-space), or nil when none does. Those objects mark
themselves (their number from 0) and, since the bank then lives in a texture, every
object whose strategy reads the bank is told (:bank-in-texture!). Returns {:list [{:id :grid}]
:anchor (the first grid's low corner: the bank's rows are about it) :textures}, or
nil and a message when a texture would not fit."
  (let [list []
        all []]
    ;; The objects a strategy grids (its :grid-boxes: an instance group's members).
    (each [_ o (ipairs tape.objects)]
      (case (?. (strategies.of o) :grid-boxes)
        grid-boxes (case (grid-boxes o (length list))
                     (boxes layout) (do (each [_ b (ipairs boxes)] (table.insert all b))
                                        (table.insert list {:id o.id : boxes : layout})))))
    ;; One frame for every grid: a ray crosses one set of walls.
    (let [f (when (> (length list) 0) (grid.frame all))]
      (each [_ e (ipairs list)]
        (set e.grid (grid.build e.boxes f))
        (set e.boxes nil)))
    ;; A blend's children (lower.fnl's :blend) in its own frame, the point's: listed
    ;; a blend radius further, on finer cells.
    ;; (Only a blend lower.fnl found prunable: one inside a smooth union, say, loops
    ;; over all its children.)
    (each [_ ins (ipairs (or tape.blends []))]
      (when ins.prunable?
        (let [g (grid.build ins.boxes nil {:grow ins.grow :cells-per-member grid.blend-cells-per-member})]
          (set ins.grid (length list))
          (set ins.grid-data g)
          (table.insert list {:blend? true :grid g :layout ins}))))
    ;; With grids the bank is a texture, which every blend reads.
    (when (> (length list) 0)
      (each [_ ins (ipairs (or tape.blends []))] (set ins.texture? true)))
    (when (> (length list) 0)
      (set tape.instances.texture? true)
      (each [_ o (ipairs tape.objects)]
        (case (?. (strategies.of o) :bank-in-texture!)
          f (f o)))
      (let [anchor (. list 1 :grid :lo)]
        (case (grid.textures (icollect [_ e (ipairs list)] e.grid)
                             (uniforms.tape-values tape.instances anchor) anchor
                             (icollect [_ e (ipairs list)] {:base e.layout.base :stride e.layout.stride}))
          tex {: list : anchor :textures tex}
          (nil err) (values nil err))))))

(fn objects-in-order [scene tape]
  "The scene's objects in shader order (the numbers gObject gives them): the tape's,
the field's and an instance group's members in turn. A scene may hold some of a
file's objects: they are found by index."
  (let [out []
        by-index (collect [_ o (ipairs scene.objects)] o.index o)]
    (each [_ o (ipairs (if tape tape.objects []))]
      (each [_ index (ipairs (or o.indices [o.index]))]
        (table.insert out (. by-index index))))
    out))

(fn lighting-plan [scene plan options]
  "Which features of the modern lighting model (`scene`'s :lighting section) the
shader of `plan` holds, and how its soft shadows march."
  (let [l scene.lighting
        ;; A softness that is a function of time may be 0 at one time and not
        ;; at another: its shader has both marches.
        animated? (accumulate [found? false _ a (ipairs (or scene.animated []))]
                    (or found? (and (= (. a.path 1) "lighting")
                                    (= (. a.path (length a.path)) "softness"))))
        soft? (and plan.shadows?
                   (accumulate [soft? animated? _ light (ipairs l.lights)]
                     (or soft? (> light.softness 0))))
        ;; A light of softness 0 among soft ones: the soft shadow keeps the
        ;; hard march for it. A softness that is a function of time may reach 0.
        hard? (accumulate [hard? (or animated? options.hard-march?) _ light
                           (ipairs l.lights)]
                (or hard? (<= light.softness 0)))
        active (features.active l)]
    {:lights (length l.lights)
     : soft?
     : hard?
     ;; Soft shadow rays may march only inside the bounding spheres grown by
     ;; the penumbra (see :soft-bounded? below), unless switched off.
     :shadow-bounds? (not= false options.shadow-bounds?)
     ;; The features it has on (src/render/features/), by name.
     :features active
     ;; Steps of a soft shadow ray at most: its penumbra estimate needs every
     ;; step, so it cannot skip empty space by bounds; a ray that has not
     ;; reached the light by then counts as lit.
     :shadow-steps 128
     ;; A feature whose distance samples the first light's soft shadow march
     ;; takes as its first turns (its descriptor's :taps; ambient occlusion's):
     ;; one copy of the scene's distance for both (issue 42). Only where every
     ;; light's shadow is that march: a hard one returns before any turn.
     :taps (when (and soft? (not hard?))
             (accumulate [found nil _ name (ipairs active)]
               (or found (when (. (features.lookup name) :taps) name))))}))

;; The fields built for a scene's objects (its list, which a load or a value edit
;; makes anew), by their options: the player's plans of one scene (the one on screen,
;; its folded twin, its still's) share one field, its textures and their images (three
;; copies of 1,000,000 spheres' field took the player to 2.8 GB). Not for a scene with
;; functions of time, whose values change in place each frame. Weak: a field goes
;; with its scene.
(local fields (setmetatable {} {:__mode :k}))
(local collect-after 100000)

(fn built-field [scene members options]
  ;; field.build of `members` (of `scene`'s objects) with `options`, once per list of
  ;; objects and options when the scene has no functions of time; nil and a message
  ;; as field.build gives them.
  (let [key (string.format "%s %s %s" (tostring options.reach-at-least) (tostring options.wide?)
                           (tostring options.cells-per-object))
        by-options (if (< 0 (length (or scene.animated []))) {}
                       (or (. fields scene.objects)
                           (let [t {}] (tset fields scene.objects t) t)))]
    (case (. by-options key)
      fd fd
      _ (case (field.build members options)
          fd (do (tset by-options key fd)
                 ;; No function of time changes its values in place: its textures'
                 ;; floats may go once a backend has them (field.release-floats!).
                 (set fd.static? (= 0 (length (or scene.animated []))))
                 ;; What the build left behind is collected at once for a large
                 ;; field, before textures and a shader come on top: LuaJIT's
                 ;; collector took its time over 600 MB of it (1,000,000 spheres).
                 (when (>= fd.count collect-after) (collectgarbage))
                 fd)
          (nil err) (values nil err)))))

(fn interpreter-count-fits? [scene]
  "Whether `scene`'s objects are few enough for the tape interpreter (without lowering
them): at most its max-objects, or more with those outside a field at most that many
(the interpreter keeps a field of a scene of more objects: scene->plan)."
  (or (<= (length scene.objects) interpret.max-objects)
      (<= (accumulate [n 0 _ o (ipairs scene.objects)]
            (if (field.member? o) n (+ n 1)))
          interpret.max-objects)))

(fn scene->plan [scene ?options]
  "Lower `scene` into a plan. Options:
  :view           :shaded (default), :normals, :glow or :heat
  :uber?          compile every kind and feature in, switched by uniforms
  :reflections    override the scene's reflection count (the player's k/l keys)
  :uniform-limit  uniform vectors the driver allows (default 4096, llvmpipe's)
  :probe?         for the probe shader: colours and mirror amounts, no lighting
  :load-once?     false: read uniforms where they are used instead of once per pixel
                  (renderer-options picks it by the renderer)
  :samples        supersampling, N x N rays per pixel (default the scene's)
  :adaptive?      true: with :samples above 1, adaptive (the player's anti-aliased
                  still); false: every pixel N x N; nil: the scene's :adaptive
  :model          :classic draws a scene that has :lighting with the article's model
                  (the player's m key)
  :field-cells    grid cells per field object (default src/render/field.fnl's)
  :fold?          true: the scene trees' values (but camera-relative positions),
                  the render settings and the lighting values (uniforms.fixed, in
                  :baked) as constants in the code, and in the key (--render,
                  --export-shader, --record of a scene without functions of time,
                  the player's shader once values settle)
The rest each switch one speed-up off (the default has it on): the tests' oracles
and `make bench`'s before (test/bench/report.fnl).
  :bounds?        false: march every object everywhere, planes too (see
                  src/render/bounds.fnl)
  :far-field?     false: no far field and no object guards in scene trees (see
                  src/sdf/lower.fnl)
  :shadow-bounds? false: soft shadow rays march the whole scene all the way, not
                  only inside the bounding spheres
  :hard-march?    true: soft shadows keep the hard march even when no light has
                  softness 0
  :field?         false: no field (src/render/field.fnl) however many spheres and
                  boxes the scene has; they go into uniform arrays
  :grids?         false: no grids over instance groups or blends (src/sdf/grid.fnl):
                  each loops over all its members, its rows in uniform arrays
  :tape-texture?  false: with :load-once?, the tape's rows in a uniform array, not a
                  texture (codegen's load-once)
  :interpret?     true: the scene drawn by the tape interpreter (src/sdf/interpret.fnl):
                  one shader for every scene of its instruction set, so a structural
                  edit needs no compile; no grids or folding, its bounds (when
                  every finite object has one) from an image. nil and why when the
                  tape cannot run on it
  :instructions   with :interpret?, an instruction set the shader holds besides the
                  scene's (interpret.instruction-set)
  :software?      true: drawn by a software renderer (renderer-options sets it), where
                  the interpreter refuses a program its loops would cut short
                  (interpret.software-fits?)
Returns the plan, or nil and a message when the scene does not fit the budget."
  (let [options (if (and ?options ?options.interpret?)
                    ;; The interpreter draws every object as it is: no grids
                    ;; (their counts would be in the shader), no values folded into
                    ;; code; its bounds from an image (see below). A field only
                    ;; where the objects are more than it runs (interpret's
                    ;; max-objects): its kinds are in the key (a new kind
                    ;; compiles), its count a uniform (interpret.tape-of).
                    (doto (collect [k v (each-pair ?options)] k v)
                      (tset :grids? false) (tset :fold? false)
                      (tset :field? (and (not= false ?options.field?)
                                         (> (length (or scene.objects [])) interpret.max-objects))))
                    (or ?options {}))
        view (or options.view :shaded)
        uber? (not (not options.uber?))
        reflections (or options.reflections scene.render.reflections)
        ;; Many spheres and boxes form a field: textures and a grid. It needs the
        ;; bounded march (see plan-bounds below).
        members (when (and (not uber?) (not= false options.field?) (not= false options.bounds?)
                           scene.render.bounds)
                  (field.members scene.objects))
        ;; Every object is lowered into the tape: the field's members as its first
        ;; object (a strategy: see lower.fnl), the others each or in groups. (A
        ;; member is what field.member? says, asked again: a set of a million members
        ;; was 60 MB of garbage for each of the player's plans.)
        (tape lower-error) (lower.lower (icollect [_ o (ipairs scene.objects)]
                                          (when (not (and members (field.member? o)))
                                            (lower.node-of o)))
                                        {:modern? (not= nil scene.lighting)
                                         :field members
                                         :far-field? options.far-field?
                                         :fold? options.fold?
                                         ;; One shader for every scene: general forms.
                                         :general-forms? options.interpret?})
        (interpreted interpret-error) (when (and tape options.interpret?)
                                        (case (interpret.tape-of tape options.instructions)
                                          (nil why) (values nil why)
                                          t (software-interpreted t options scene)))
        shaded? (= view :shaded)
        plan {: view : uber?
              :load-once? (not= false options.load-once?)
              ;; Read once per pixel, the tape's rows come from a texture: far
              ;; quicker for llvmpipe to compile than uniforms (codegen's load-once).
              :tape-texture? (and (not= false options.load-once?)
                                  (not= false options.tape-texture?))
              ;; The objects in shader order (the numbers gObject gives them): the
              ;; tape's (the field's and an instance group's members in turn).
              :objects (objects-in-order scene tape)
              :tape (or interpreted tape (lower.lower []))
              :mirrors? (and tape tape.mirrors?
                             (or options.probe? (and shaded? (or uber? (> reflections 0)))))
              :shadows? (and shaded? (or uber? scene.render.shadows))
              :reflections? (and shaded? (or uber? (> reflections 0)))
              :glow? (and shaded? (or uber? scene.render.glow))
              ;; A field's walk takes plain steps (march.glsl's field forms).
              :relaxed? (and (= nil members) (or uber? (> scene.render.relaxation 1)))
              :hit-test scene.render.hit-test
              :out-of-steps (or scene.render.out-of-steps :background)
              :samples (or options.samples scene.render.samples 1)
              ;; Extra samples only at edges: the shaded view's (it has the normals).
              :adaptive? (and (> (or options.samples scene.render.samples 1) 1) shaded?
                              (if (= nil options.adaptive?) (= true scene.render.adaptive)
                                  (= true options.adaptive?)))
              :edge-tests edge-tests
              ;; Only the shaded and normals views compute normals.
              :normals (when (or shaded? (= view :normals)) scene.render.normals)
              :normals-of (or scene.render.normals-of :object)
              : reflections}
        limit (or options.uniform-limit default-uniform-limit)]
    (assert (view? view) (.. "unknown view " (tostring view)))
    (var grid-error nil)
    (case (if (not= false options.grids?) (grids-of plan.tape) nil)
      gs (set plan.grids gs)
      (nil err) (set grid-error (.. scene.file ": objects: " err)))
    ;; A march through grids steps to cell walls along its ray, which over-relaxation's
    ;; overlapping spheres do not cover: plain steps, as a field's march.
    (when plan.grids (set plan.relaxed? false))
    (set plan.uniform-vectors (+ fixed-uniform-vectors (length plan.tape.rows)
                                 (if plan.grids
                                     (* 3 (length plan.grids.list))
                                     (length plan.tape.instances.rows))))
    ;; Bounds take a vector each: a scene that fits only without them goes without.
    ;; The interpreter's come in an image with their count, which is not in its text.
    (let [b (bounds.plan-bounds plan scene options)]
      (if (and b options.interpret?) (set plan.bounds {:texture? true})
          (and b (<= (+ plan.uniform-vectors b.count) limit))
          (do (set plan.bounds b)
              (set plan.uniform-vectors (+ plan.uniform-vectors b.count)))))
    ;; The modern lighting model (a :lighting section): which of its features the
    ;; shader holds.
    (when (and shaded? scene.lighting (not options.probe?) (not= options.model :classic))
      (set plan.lighting (lighting-plan scene plan options)))
    (var field-error nil)
    (when members
      (case (built-field scene members
                         {:reach-at-least (when plan.lighting
                                            (accumulate [r nil _ name (ipairs plan.lighting.features)]
                                              (let [d (features.lookup name)]
                                                (if d.reach (math.max (or r 0) (d.reach scene.lighting)) r))))
                          :wide? (and plan.lighting plan.lighting.soft?)
                          :cells-per-object options.field-cells})
        fd (set plan.field fd)
        (nil err) (set field-error (.. scene.file ": " err))))
    ;; Soft shadow rays march the finite objects only over their bounding spheres'
    ;; span, the planes met in closed form, as primary rays do: with bounds and no
    ;; field (a field's objects are not among the finite ones). The shader
    ;; (codegen's modern-lines) and the CPU reference (lighting.fnl) both read this.
    (when plan.lighting
      (set plan.lighting.soft-bounded? (and plan.lighting.soft? plan.lighting.shadow-bounds?
                                            (not= nil plan.bounds) (= nil plan.field))))
    ;; When every object has its exact normal in closed form (a field's, and the
    ;; tape's leaves whose primitive has its gradient), normals need no differences
    ;; (shaders/pipeline/normal-exact.glsl).
    ;; (Never the interpreter's: whether every object of the program has one is not
    ;; in its text; normal-crease.glsl's exact slot asks the program per object.)
    (set plan.exact-normals? (and (= plan.normals-of :object) (not options.interpret?)
                                  (accumulate [all? true _ o (ipairs plan.tape.objects)]
                                    (and all? (emit-glsl.exact? o)))))
    ;; Folded: the settings and lighting values as constants too (what no view
    ;; changes; the export writes every value so), each as its GLSL declaration, and so
    ;; in the key.
    (when (and options.fold? (not uber?))
      (set plan.baked (collect [_ u (ipairs (uniforms.fixed scene plan))]
                        u.name (uniforms.constant u))))
    ;; Rows from a texture: the values a pixel copies once ride it too, after the
    ;; rows, for when no flat varying is left for them (codegen's load-once).
    (when (and plan.tape-texture? (> (length plan.tape.rows) 0))
      (set plan.texels (uniforms.texel-layout scene plan)))
    (set plan.key (structure-key plan))
    (if field-error (values nil field-error)
        grid-error (values nil grid-error)
        (and members (not plan.bounds))
        ;; Some other object has no bound (an infinite repetition, a plane inside a
        ;; tree): no field then, and the uniform budget decides.
        (scene->plan scene (doto (collect [k v (each-pair options)] k v) (tset :field? false)))
        lower-error (values nil (.. scene.file ": " lower-error))
        interpret-error (values nil (.. scene.file ": the interpreter cannot draw it: " interpret-error))
        (> (written-nodes plan.tape) max-written-nodes)
        (values nil (nodes-message scene plan.tape))
        (> plan.uniform-vectors limit) (values nil (budget-message scene plan limit))
        plan)))

{: scene->plan : views : view? : default-uniform-limit : fixed-uniform-vectors
 : software-renderer? : renderer-options : structure-key
 : interpreter-count-fits?}

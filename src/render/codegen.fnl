;; Code generation: a plan becomes one GLSL fragment shader, assembled from the chunks in
;; shaders/ and holding only what the plan needs. Output is deterministic: the same plan
;; always gives the same text.

(local emit-glsl (require :src.sdf.emit-glsl))
(local bounds (require :src.render.bounds))
(local strategies (require :src.sdf.strategies))
(local features (require :src.render.features))

(local {: flatten-into : fill : parts : fill-part : chunk-error? : set-reader!}
  (require :src.render.chunks))

;;; Objects: the tape's, each drawn by its strategy (src/sdf/emit-glsl.fnl).

(fn object-normals? [plan]
  ;; Normals from the nearest object's own distance (see map-object.glsl).
  (and (not= nil plan.normals) (= plan.normals-of :object)))

(fn modern-materials? [plan]
  (or (not= nil plan.lighting) (and plan.tape (= plan.tape.material-size 8))))

(fn long-array? [count]
  ;; An array code indexes in a loop that load-once leaves a uniform (read where
  ;; used): one longer than emit-glsl.max-copied-array.
  (> count emit-glsl.max-copied-array))

(fn uniform-declarations [plan]
  (let [lines []]
    (when (> plan.tape.count 0)
      (table.insert lines (.. "// objects: " plan.tape.count))
      (flatten-into lines "" (emit-glsl.declarations plan.tape)))
    (when plan.grids
      (table.insert lines (emit-glsl.declare "vec4" "uGrids" (* 3 (length plan.grids.list))
                                             "per grid: low corner, reach; cell, first cell; cells along each axis")))
    ;; The interpreter's spheres come in an image, declared with the functions that
    ;; read it (bounds.glsl's spheres-texture part).
    (when (and plan.bounds (not plan.bounds.texture?) (> plan.bounds.count 0))
      (table.insert lines (emit-glsl.declare "vec4" "uBounds" plan.bounds.count
                                             "bounding spheres of the finite objects (camera-relative)"
                                             (long-array? plan.bounds.count))))
    (when (object-normals? plan)
      (table.insert lines "int gObject = -1;  // the object mapColor found nearest last (-1: none)"))
    (let [modern? (modern-materials? plan)]
      (when (or plan.mirrors? modern?)
        (table.insert lines (.. "float gMirror = " (if modern? "0.0" "1.0")
                                ";  // mirror amount of what mapColor found last")))
      (when modern?
        (table.insert lines "vec4 gMaterial = vec4(0.5, 0.0, 0.0, 0.0);  // its roughness and emission")))
    (when plan.lighting
      (let [l plan.lighting]
        (table.insert lines (.. "// modern lighting: " l.lights (if (= l.lights 1) " light" " lights")))
        (table.insert lines (.. "const int kLightCount = " l.lights ";"))
        (when l.soft? (table.insert lines (.. "const int kShadowSteps = " l.shadow-steps ";")))
        (each [_ [ty name count note loop?]
               (ipairs [["vec4" "uLights" l.lights "point: position, range; sun: direction, 0"
                         (long-array? l.lights)]
                        ["vec4" "uLightColors" l.lights "linear colour times intensity, softness"
                         (long-array? l.lights)]
                        ["vec3" "uSkyZenith" nil "linear"]
                        ["vec3" "uSkyHorizon"]
                        ["vec2" "uSunEdge" nil "cosines of the sun disc's outer, inner radius"]
                        ["float" "uAmbient"]
                        ["float" "uExposure"]])]
          (table.insert lines (emit-glsl.declare ty name count note loop?)))
))
    lines))

(fn distance-terms [cx plan]
  (emit-glsl.distance-terms cx plan.tape))

(fn soft-bounded? [plan]
  ;; See plan.lighting.soft-bounded? in src/render/plan.fnl.
  (= true (?. plan :lighting :soft-bounded?)))

(fn taps-of [plan]
  ;; The :taps of the feature whose samples the soft shadow march takes
  ;; (plan.lighting's :taps; see src/render/features.fnl), or nil.
  (case (?. plan :lighting :taps)
    name (. (features.lookup name) :taps)))

(fn map-some? [plan]
  ;; mapSome(p, planes): the bounded soft march that takes samples reads the
  ;; half-spaces at them (shaders/pipeline/bounds.glsl); map and mapFinite call it.
  (and (soft-bounded? plan) (not= nil (taps-of plan))))

(fn span-lines [b grown?]
  ;; boundsSpan, and with `grown?` boundsSpanGrown (soft shadows): the same loop over
  ;; the bounding spheres, the second growing each (shaders/pipeline/bounds.glsl):
  ;; uBounds' n, or with :texture? as many as its first texel says (the
  ;; interpreter's: the count is not in the text).
  (let [path "shaders/pipeline/bounds.glsl"
        part (if grown? :span-grown :span)
        loop #(fill-part path (.. part "-loop") $)]
    (fill-part path part {:spheres (if b.texture? (loop {:count "boundsCount()" :sphere "boundsSphere(i)"})
                                       (> b.count 0) (loop {:count (tostring b.count)
                                                                 :sphere "uBounds[i]"})
                                       [])})))

(fn bounded-lines [cx plan]
  "mapFinite, planesHit and boundsSpan: what the bounded march reads (see
src/render/bounds.fnl and shaders/pipeline/bounds.glsl)."
  (let [path "shaders/pipeline/bounds.glsl"
        planes (emit-glsl.plane-terms cx plan.tape)]
    [(if (map-some? plan)
         (fill-part path :map-finite-some {})
         (fill-part path :map-finite {:distance-terms (emit-glsl.distance-terms cx plan.tape true)}))
     ""
     (fill-part path :planes-hit {:plane-terms (if (> (length planes) 0) ["vec3 p = ro;" planes] [])})
     ""
     (if plan.bounds.texture? [(fill-part path :spheres-texture {:width (tostring bounds.texture-width)}) ""] [])
     (span-lines plan.bounds false)
     (if (soft-bounded? plan) ["" (span-lines plan.bounds true)] [])]))

(fn color-start [plan]
  ;; What mapColor's query sets first: no mirror and the default material, no object.
  [(if (modern-materials? plan) "gMirror = 0.0; gMaterial = vec4(0.5, 0.0, 0.0, 0.0);"
       plan.mirrors? "gMirror = 1.0;"
       [])
   (if (object-normals? plan) "gObject = -1;" [])])

(fn color-terms [cx plan]
  [(color-start plan)
   (emit-glsl.color-terms cx plan.tape plan.mirrors? (when (object-normals? plan) 0))])

(fn crease? [plan]
  ;; Object normals by differences (normal-crease.glsl): mapObject answers every
  ;; query of a hit, mapColor's too, written once.
  (and (object-normals? plan) (not plan.exact-normals?)))

(fn gradient-terms [cx plan action]
  ;; Each object's exact normal in closed form, when gObject is its number (a field
  ;; member's, a leaf's its primitive's gradient); `action` is "n = "
  ;; (normal-exact.glsl) or "return " (the exact slot of normal-crease.glsl).
  (emit-glsl.gradient-terms cx plan.tape 0 action))

(fn object-terms [cx plan]
  ;; mapObject's cases: each tape object (a field's member) by number, or every one
  ;; but one, or mapColor's query.
  (emit-glsl.object-terms cx plan.tape 0 plan.mirrors?))

;;; Features

(fn when-switched [plan switch lines]
  ;; In the all-features (uber) shader a feature is compiled in and switched by a
  ;; uniform; in a specialized shader it is either there or absent.
  (if plan.uber?
      [(.. "if (" switch ") {") (icollect [_ l (ipairs lines)] (.. "    " l)) "}"]
      lines))

(fn feature-uniforms [plan]
  (let [lines []]
    (when plan.reflections? (table.insert lines (emit-glsl.declare "int" "uReflections")))
    (when plan.relaxed?
      (table.insert lines (emit-glsl.declare "float" "uRelaxation" nil "over-relaxation factor")))
    (when plan.uber?
      (table.insert lines (emit-glsl.declare "bool" "uShadows"))
      (table.insert lines (emit-glsl.declare "bool" "uGlow")))
    lines))

(fn along-lines [cx plan]
  "With grids, the distance a march takes, along its ray rd (mapAlong, or with bounds
mapFiniteAlong): map's or mapFinite's terms, each grid bounding its unlisted members
along the ray (see gridCellAlong in shaders/pipeline/grid.glsl)."
  (if plan.grids
      (let [bounded? (not= nil plan.bounds)]
        (fill-part "shaders/pipeline/bounds.glsl" :along
                   {:name (if bounded? "mapFiniteAlong" "mapAlong")
                    :distance-terms (emit-glsl.distance-terms cx plan.tape bounded? true)}))
      []))

(fn march-map [plan]
  ;; The march's distance call: map's or mapFinite's, along the ray with grids.
  (.. (if plan.bounds "mapFinite" "map") (if plan.grids "Along" "")))

(fn march-form [plan]
  ;; The plan's form of the primary march (shaders/pipeline/march.glsl): sphere
  ;; tracing (:trace), or through a field's grid: the general walk, beside other
  ;; finite objects (:field), or a lean walk of the field alone: one cell a turn
  ;; (:cells), or a field of spheres only, one texel a turn (:spheres).
  (if (not plan.field) :trace
      (bounds.others? plan) :field
      plan.field.walk? :spheres
      :cells))

(fn march-lines [plan count-step out-of-steps]
  "The primary march, raymarchTo (raymarch when unbounded), from
shaders/pipeline/march.glsl alone: its skeleton (part march) with the slots filled
by the parts of the plan's form (march-form): sphere tracing, plain or
over-relaxed, over the whole scene or bounded (mapFinite over the bounding spheres'
span, planes in closed form); or a walk through a field's grid, the general one
(the other finite objects sphere-traced alongside) or a lean one. `count-step` and
`out-of-steps` fill the slots of those names."
  (let [path "shaders/pipeline/march.glsl"
        bounded? (not= nil plan.bounds)
        part #(fill-part path $1 (or $2 {}))
        ;; Sphere tracing's distance at each step (the general walk's as well).
        trace-step #(part :trace-step {:map (march-map plan)
                                       :ray (if plan.grids ", rd" "")
                                       :first (if bounded? "t == 0.0 && " "")})
        slots (case (march-form plan)
                :trace {:about (part :about-trace)
                        :start [(part :trace-start)
                                (if bounded? (part :start-bounded {:grid-span []})
                                    (part :start-unbounded))
                                (if plan.relaxed?
                                    (part :relaxed-state {:t-prev (if bounded? "t" "0.0")})
                                    [])]
                        :before-loop [(if bounded? (part :before-bounded) []) (part :trace-before)]
                        :turns "uMaxSteps"
                        :step [(trace-step)
                               (if plan.relaxed?
                                   (part :step-relaxed
                                         {:count-step count-step
                                          :relaxed-end (part (if bounded? :relaxed-end-bounded
                                                                 :relaxed-end-unbounded))})
                                   (part (if bounded? :step-plain-bounded :step-plain)
                                         {:count-step count-step}))]}
                ;; (A field's forms count their own steps: cells and points evaluated.)
                :field {:about (part :about-field)
                        :start [(part :trace-start)
                                (part :start-bounded {:grid-span (part :grid-span)})]
                        :before-loop [(part :before-bounded) (part :walk-state) (part :trace-before)]
                        :turns "uMaxSteps + uFieldCrossings + 1"
                        :step [(part :cell-enter) (trace-step) (part :step-field)]}
                :cells {:about (part :about-cells)
                        :start (part :start-walk)
                        :before-loop (part :before-walk)
                        :turns "uFieldCrossings + 1"
                        :step (part :step-cells)}
                :spheres {:about (part :about-spheres)
                          :start (part :start-walk)
                          :before-loop [(part :before-walk) (part :spheres-state)]
                          :turns "uFieldTurns + 1"
                          :step (part :step-spheres)})]
    [(part :march (doto slots
                    (tset :march (if bounded? "raymarchTo" "raymarch"))
                    (tset :range (if bounded? "float tMax, " ""))
                    (tset :out-of-steps out-of-steps)))
     (if bounded? ["" (part :to-draw-distance)] [])]))

(fn mirror-slots [plan]
  ;; Part-mirror materials add a few lines to the bounce loop; other scenes get none,
  ;; so their shaders stay as they were.
  (if plan.mirrors?
      (let [p (parts "shaders/shading/mirror.glsl")]
        {:mirror-start p.start :mirror-before p.before :mirror-mix p.mix :mirror-next p.next})
      {:mirror-start [] :mirror-before [] :mirror-mix [] :mirror-next []}))

(fn modern-lines [plan]
  "The modern model's functions (sky, occlusion, fog, shadows, direct light), each
only when the plan has it. A feature's distance samples may be the first turns of
the soft shadow march (its :taps: one copy of the scene for both)."
  (let [l plan.lighting
        march (if plan.bounds
                  "float ts = raymarchTo(o, l, reach, shadowSteps);"
                  "float ts = raymarch(o, l, shadowSteps);")
        taps (taps-of plan)
        tap-part #(if taps (fill-part taps.chunk $1 {}) $2)]
    [(fill "shaders/shading/modern/sky.glsl" {})
     (icollect [_ name (ipairs l.features)] (fill (. (features.lookup name) :chunk) {}))
     (if (not plan.shadows?) []
         l.soft? (fill "shaders/shading/modern/shadow-soft.glsl"
                       {:hard-shadow (if l.hard?
                                         ["if (softness <= 0.0) {"
                                          ["    int shadowSteps;" (.. "    " march)
                                           "    return ts < reach ? 0.0 : 1.0;"]
                                          "}"]
                                         [])
                        :soft-span (if (soft-bounded? plan)
                                       (fill-part "shaders/pipeline/bounds.glsl" :soft-span
                                                  (if taps
                                                      {:blocked-by-plane ["seen = 0.0;" "reach = -1.0;"]
                                                       :empty-span []}
                                                      {:blocked-by-plane ["return 0.0;"]
                                                       :empty-span ["if (t >= reach) {" "    return 1.0;" "}"]}))
                                       [])
                        :params (table.concat (tap-part :params [""]) "")
                        :first-turn (if taps "gZero - taps" "0")
                        :taps-start (tap-part :start [])
                        :turn (tap-part :turn ["vec3 q = o + l * t;"])
                        :take (tap-part :take [])
                        :taps-end (tap-part :end [])
                        ;; Nothing returns before the samples are taken.
                        :blocked (if taps ["seen = 0.0;" "break;"] ["return 0.0;"])
                        :soft-map (let [read (if (map-some? plan) "mapSome(q, tap);"
                                                 (soft-bounded? plan) "mapFinite(q);"
                                                 "map(q);")]
                                    (if plan.tape.estimates?
                                        [(.. "float h = " read) "gEstimate = true;"
                                         (.. "float he = " read) "gEstimate = false;"]
                                        [(.. "float h = " read) "float he = h;"]))
                        :soft-along [(if plan.tape.estimates?
                                         "float y = (hPrev * hPrev - hePrev * hePrev + he * he) / (2.0 * hPrev);"
                                         "float y = he * he / (2.0 * hePrev);")]})
         (fill "shaders/shading/modern/shadow-hard.glsl" {:shadow-march [march]}))
     (fill "shaders/shading/modern/lights.glsl"
           {:params (if taps ", inout float occ" "")
            ;; The first light's march takes the samples whether the light reaches
            ;; the point or not (reach -1: no shadow turn).
            :shadow-taps (if taps
                             [(.. "visible = visibility(origin, l, lambert > 0.0 ? reach : -1.0, "
                                  "uLightColors[i].w, i == 0 ? " taps.count " : 0, p, n, occ);")]
                             [])
            :shadow (if (and plan.shadows? (not taps))
                        ["visible = visibility(origin, l, reach, uLightColors[i].w);"]
                        [])
            :light (features.slot-lines l.features :light)})]))

(fn primary-in-loop? [plan]
  "Whether the primary ray is marched as turn 0 of the modern view's bounce loop: one
call of raymarch, so one copy of the scene's march, where the primary march before
the loop and the bounce's inside it were two (GLSL compilers inline every call: a
copy costs its share of the compile, issue 42). The adaptive test reads the primary
hit there too, after its surfaceAt (view-lines' primary-hit). (The classic view's
primary hit stays before its bounce loop: in the loop, gallery's frames took 1.48
times as long on llvmpipe; see docs/benchmarks.md.)"
  (and (= plan.view :shaded) (not= nil plan.lighting)))

(fn view-lines [plan]
  ;; The adaptive edge test of the centre ray, on its primary hit's normal
  ;; (adaptive.glsl's needsSamples): at turn 0 of the modern view's bounce loop, or
  ;; before the classic view's.
  (local primary-hit (if (not plan.adaptive?) []
                         (primary-in-loop? plan) ["if (gCentre && bounce == 0) {"
                                                  "    gNeedsSamples = needsSamples(dir, t, n);"
                                                  "}"]
                         ["if (gCentre) {"
                          "    gNeedsSamples = needsSamples(rd, t, n);"
                          "}"]))
  (case plan.view
    :shaded (if plan.lighting
                (fill "shaders/views/modern.glsl"
                      {:bounce-loop [(.. "for (int bounce = 0; bounce <= "
                                         (if plan.reflections? "uReflections" "0") "; bounce++) {")]
                       :march ["t = raymarch(origin, dir, steps);"]
                       :primary-hit primary-hit
                       :light-args (if (taps-of plan) ", occ" "")
                       :occlusion (features.slot-lines plan.lighting.features :occlusion
                                                       plan.lighting.taps)
                       :surface (features.slot-lines plan.lighting.features :surface)
                       :segment (features.slot-lines plan.lighting.features :segment)})
                (fill "shaders/views/shaded.glsl"
                  {:glow (if plan.glow? (when-switched plan "uGlow" (fill "shaders/shading/glow.glsl" {})) [])
                   : primary-hit
                   :reflections (if plan.reflections?
                                    (fill "shaders/shading/reflect.glsl" (mirror-slots plan))
                                    [])}))
    :normals (fill "shaders/views/normals.glsl"
                   ;; The nearest object's normal needs it found first (surfaceAt).
                   {:normal (if (object-normals? plan)
                                ["vec3 surface;" "return surfaceAt(ro + rd * t, surface) * 0.5 + 0.5;"]
                                ["return calcNormal(ro + rd * t) * 0.5 + 0.5;"])})
    view (fill (.. "shaders/views/" view ".glsl") {})))

(fn out-of-steps-lines [plan]
  ;; A ray that spends its step budget without meeting the hit test: the article
  ;; shades it where it stopped (:surface); :background treats it as passing every
  ;; finite object, so it meets a ground plane if one lies ahead, else the sky.
  (case plan.out-of-steps
    :surface []
    :background (if plan.bounds ["return min(tPlane, tMax);"] ["return uDrawDist;"])))

(fn shader-hooks [plan part]
  ;; The tape objects' strategies' shader parts `part` (src/sdf/strategies.fnl's
  ;; :shader), each a function of what it needs but plan and object (given here):
  ;; :functions (fn [defined]) -> sections, :gradients (fn [defined]) -> lines or
  ;; nil, :sections (fn []) -> a section, with the chunk system's fill.
  (icollect [_ o (ipairs plan.tape.objects)]
    (case (?. (strategies.of o) :shader part)
      f (fn [...] (f plan o fill ...)))))

(fn body-lines [cx plan]
  (let [view plan.view
        normals? (or (= view :shaded) (= view :normals))
        ;; The normals view reads mapColor's gObject when normals are the object's.
        colors? (or (= view :shaded) (= view :glow) (and (= view :normals) (object-normals? plan)))
        sections [(fill "shaders/pipeline/prelude.glsl" {:feature-uniforms (feature-uniforms plan)})
                  (uniform-declarations plan)]]
    ;; Distance functions: the tape's, each once, and the exact gradients its leaves
    ;; and a field's objects (fieldNormal: the box's) take.
    (let [defined {}]
      ;; Instance groups with grids read their rows and cells from textures.
      (when plan.grids
        (table.insert sections (fill "shaders/pipeline/grid.glsl" {})))
      (table.insert sections (emit-glsl.functions plan.tape defined))
      ;; What a strategy's own functions need (a field's marched members call their
      ;; primitives).
      (each [_ f (ipairs (shader-hooks plan :functions))]
        (each [_ section (ipairs (f defined))]
          (table.insert sections section)))
      ;; Exact normals take every leaf's gradient; planesHit, the half-spaces'; then
      ;; what a strategy's exact normals call (a field's, the box's).
      (let [hooks (shader-hooks plan :gradients)]
        (when (or (> (length hooks) 0) (and normals? (object-normals? plan)) plan.bounds)
          (let [normals? (and normals? (object-normals? plan))
                gradients (emit-glsl.gradient-functions
                           plan.tape #(or normals? (and (not= nil plan.bounds) $.half-space?))
                           defined)]
            (each [_ f (ipairs hooks)]
              (case (f defined)
                lines (do (when (> (length gradients) 0) (table.insert gradients ""))
                          (flatten-into gradients "" lines))))
            (table.insert sections gradients)))))
    ;; The hit test, before a field's marched members take it; then a strategy's own
    ;; functions (a field's walk, shaders/pipeline/field.glsl).
    (table.insert sections (fill (.. "shaders/pipeline/hit/" plan.hit-test ".glsl") {}))
    (each [_ f (ipairs (shader-hooks plan :sections))]
      (table.insert sections (f)))
    (table.insert sections
                  (if (map-some? plan)
                      (let [path "shaders/pipeline/bounds.glsl"]
                        [(fill-part path :map-some {:distance-terms (emit-glsl.some-terms cx plan.tape "planes")})
                         ""
                         (fill-part path :map-some-all {})])
                      (fill "shaders/pipeline/map.glsl" {:distance-terms (distance-terms cx plan)})))
    ;; mapColor only where the view has a use for colours: with crease normals, through
    ;; mapObject, which writes the scene once for every query of a hit.
    (when (crease? plan)
      (table.insert sections (fill "shaders/pipeline/map-object.glsl"
                                   {:color-start (color-start plan)
                                    :object-terms (object-terms cx plan)})))
    (when colors?
      (table.insert sections (if (crease? plan)
                                 (fill "shaders/pipeline/map-color-object.glsl" {})
                                 (fill "shaders/pipeline/map-color.glsl" {:color-terms (color-terms cx plan)}))))
    (when plan.bounds
      (table.insert sections (bounded-lines cx plan)))
    (when plan.grids
      (table.insert sections (along-lines cx plan)))
    ;; Only the glow and heat views read the step count; elsewhere it is not kept.
    (let [count-step (if (or plan.glow? (= view :glow) (= view :heat))
                         ["steps = i + 1;"] [])]
      (table.insert sections (march-lines plan count-step (out-of-steps-lines plan))))
    (when normals?
      ;; The method's taps differentiate the scene's map (normal-scene.glsl), or with
      ;; object normals the nearest object's (mapObject, normal-crease.glsl).
      (table.insert sections (fill "shaders/pipeline/normal.glsl"
                                   {:method (if plan.exact-normals? []
                                                (fill (.. "shaders/pipeline/normal/" plan.normals ".glsl") {}))}))
      (when (not (object-normals? plan))
        (table.insert sections (fill "shaders/pipeline/normal-scene.glsl" {})))
      (when (and (object-normals? plan) plan.exact-normals?)
        (table.insert sections (fill "shaders/pipeline/normal-exact.glsl"
                                     {:gradients (gradient-terms cx plan "n = ")})))
      ;; surfaceAt: a hit's colour and normal. With crease normals one loop of
      ;; mapObject (the grouped and field objects have their exact gradient; the
      ;; trees' take differences); else mapColor, then calcNormal.
      (if (crease? plan)
          (table.insert sections
                        (fill "shaders/pipeline/normal-crease.glsl"
                              {:exact (gradient-terms cx plan "return ")}))
          colors?
          (table.insert sections (fill "shaders/pipeline/surface.glsl" {}))))
    (when (and (= view :shaded) (not plan.lighting))
      (table.insert sections
                    (fill "shaders/shading/light.glsl"
                          {:shadow (if plan.shadows?
                                       (when-switched plan "uShadows"
                                                     (fill (if plan.bounds
                                                               "shaders/shading/shadow-to-light.glsl"
                                                               "shaders/shading/shadow.glsl")
                                                           {}))
                                       [])})))
    (when (and (= view :shaded) plan.lighting)
      (each [_ s (ipairs (modern-lines plan))] (table.insert sections s)))
    (when plan.adaptive?
      ;; The edge tests, before render() calls them; the averaging render() after.
      (let [tests plan.edge-tests
            constants [(.. "const int kSamples = " plan.samples ";")
                       (string.format "const float kGrazing = %.2f;    // cosine of the view to the normal"
                                      tests.grazing)
                       (string.format "const float kEdgeTurn = %.6f;  // 1 - cosine: a turn this large is an edge"
                                      tests.edge-turn)
                       (string.format "const float kLimbTurn = %.6f;  // and this large where the view grazes"
                                      tests.limb-turn)
                       (string.format "const vec2 kSecond = vec2(%.6f, %.6f);  // the second ray, from the centre"
                                      (- (. tests.second 1) 0.5) (- (. tests.second 2) 0.5))
                       (string.format "const float kContrast = %.6f;  // a luma difference this large is an edge"
                                      tests.contrast)]]
        (table.insert sections (fill-part "shaders/pipeline/adaptive.glsl" :tests {: constants}))))
    ;; With supersampling render() is one sample (renderSample); the entry point's
    ;; render() averages N x N of them.
    (table.insert sections (fill "shaders/pipeline/render.glsl"
                                 {:render (if (> plan.samples 1) "renderSample" "render")
                                  :primary [(if (primary-in-loop? plan)
                                                "float t = 0.0;  // marched as turn 0 of the view's loop"
                                                "float t = raymarch(ro, rd, steps);")]
                                  :view (view-lines plan)
                                  ;; The centre ray's edge test: after the view's
                                  ;; primary surfaceAt (view-lines' primary-hit),
                                  ;; false on a miss.
                                  :adaptive (if plan.adaptive?
                                                ["if (gCentre) {"
                                                 "    gNeedsSamples = false;"
                                                 "}"]
                                                [])}))
    (when (> plan.samples 1)
      (let [grid (parts "shaders/pipeline/supersample.glsl")]
        (table.insert sections
                      [(if plan.adaptive? [] [(.. "const int kSamples = " plan.samples ";")])
                       ;; (The adaptive render takes the grid's rays in its own loop.)
                       (if plan.adaptive? [] grid.grid)
                       (if plan.adaptive?
                           (. (parts "shaders/pipeline/adaptive.glsl") :render)
                           grid.render)])))
    sections))

(local targets
  {:love {:header ["#pragma language glsl3"] :entry "shaders/entry/love.glsl" :varyings? true}
   ;; The same without the vertex stage, for a driver with fewer varyings.
   :love-uniforms {:header ["#pragma language glsl3"] :entry "shaders/entry/love.glsl"}
   :core {:header ["#version 330 core" "out vec4 fragColor;"] :entry "shaders/entry/core.glsl"}
   :probe {:header ["#pragma language glsl3"] :entry "shaders/entry/probe.glsl"}
   :shadertoy {:header [] :entry "shaders/entry/shadertoy.glsl"}})

;; Uniforms the shader reads once per pixel: llvmpipe turns every read of a uniform
;; inside the march into an eight-lane gather and hoists nothing out of loops, so each
;; uniform is copied element by element into a private global (uName -> gName) at the
;; top of the entry point, and the code reads the global. (A whole-array copy is folded
;; back into uniform reads.) Arrays indexed in a loop (a kind with many objects) stay
;; uniforms: a private array indexed by a variable is not kept in registers, and 300
;; spheres took llvmpipe 25 s to compile that way, for no faster frame. Not the
;; lights and the bounding spheres when there are few (emit-glsl.max-copied-array):
;; their loops run a constant count and are unrolled, each element read at a constant
;; index (the tower: 7% off the compile, frames 0.94-1.00 across the showcase). The
;; resolution is read once per pixel anyway.
(local read-directly {:uResolution true})

;; Each copy is made through a value the compiler cannot fold away: a float plus
;; `nothing`, 0 divided by the pixel's x (x is at least a half, but for all the
;; compiler knows it could be 0; it does fold 0 times x), an integer through a min
;; with `opaque`, the largest int less int(nothing). Copied plainly, Mesa's compiler puts the uniform back into the loops
;; that use the copy, and llvmpipe reads it there on every turn, an eight-lane gather
;; (found in the disassembly of a field's walk: the draw distance, the step budget and
;; the turn bound were read so, three gathers in a loop of 296 instructions; through
;; these values the loop is 205).
(local nothing "0.0 / gl_FragCoord.x")

(local opaque-types {:int "min(%s, opaque)" :ivec2 "min(%s, opaque)" :ivec3 "min(%s, opaque)"
                     :ivec4 "min(%s, opaque)" :bool "(%s && opaque > 0)"
                     :float "(%s + nothing)" :vec2 "(%s + nothing)" :vec3 "(%s + nothing)"
                     :vec4 "(%s + nothing)"})

;; On llvmpipe even a uniform copied once per pixel is an eight-lane gather per
;; component (91 in the seed's shader, half its time with no shadows or mirrors), while
;; a flat varying is a broadcast. So LÖVE's shaders read the copies from flat vec4
;; varyings that a vertex stage fills from the uniforms, four vertices a frame; value
;; edits still need no compile. Drivers give a vertex stage 32 vec4 outputs (GL 3.3
;; promises only 16) and LÖVE takes 2: up to 28 here, the rest read from the uniforms
;; (the tape's rows: from their texture) as before; a driver that refuses gets the
;; :love-uniforms shader (gpu.compile-plan).
;; Integers travel as floats (exact below 2^24: step budgets, counts).
(local max-varyings 28)
(local varying-sizes {:float 1 :vec2 2 :vec3 3 :vec4 4 :int 1})

(fn pack-varyings [reads]
  ;; Flat varyings for the uniform reads `reads` ([{:read "uX[0]" :ty ty}]) that
  ;; fit: vec4 slots filled in order, a value never split across two. Returns read ->
  ;; what the pixel stage reads instead, and the vertex stage's lines.
  (let [slots []
        instead {}]
    (each [_ {: read : ty} (ipairs reads)]
      (let [n (. varying-sizes ty)
            last (. slots (length slots))
            slot (if (not n) nil
                     (and last (<= (+ last.used n) 4)) last
                     (< (length slots) max-varyings) (let [s {:used 0 :parts []}]
                                                       (table.insert slots s)
                                                       s))]
        (when (and n slot)
          (let [name (.. "vLoad" (- (length slots) 1))
                swizzle (: "xyzw" :sub (+ slot.used 1) (+ slot.used n))]
            (tset instead read (if (= ty :int) (.. "int(" name "." swizzle ")")
                                   (.. name "." swizzle)))
            (table.insert slot.parts (if (= ty :int) (.. "float(" read ")") read))
            (set slot.used (+ slot.used n))))))
    (values instead
            (when (> (length slots) 0)
              (icollect [i s (ipairs slots)]
                (.. "    vLoad" (- i 1) " = vec4(" (table.concat s.parts ", ")
                    (if (< s.used 3) (.. ", vec" (- 4 s.used) "(0.0)")
                        (= s.used 3) ", 0.0" "")
                    ");"))))))

;; How a declaration is written: as itself, unless the caller says otherwise (the
(fn default-declaration [d] d.text)

;; The tape's rows from a texture (the plan's :tape-texture?), and after them a texel
;; for each value a pixel copies once (plan :texels, uniforms.texel-layout), read
;; there when no varying is left for it: llvmpipe compiles each
;; uniform element a shader reads into an eight-lane gather, and their compile time
;; grows faster than their number (a shader reading 70 vec4 uniforms: 145 ms, 140:
;; 329 ms, 280: 971 ms; as texel fetches of an rgba32f image 46, 70 and 137 ms; as
;; constants 33, 42 and 60 ms: tools/uniform-cost), and organic's 71 rows were a
;; third of its compile. The rows that fit in the flat varyings are fetched by the
;; vertex stage (a broadcast to each pixel, as before; fetched by the pixels they cost
;; 5-8% of a frame), the rest by the pixels.
(fn rows-texture-declaration [d]
  (.. "uniform sampler2D " d.name ";  // " d.count " rows, one texel each (see load-once)"))

(fn row-fetch [name row]
  (let [(x y) (emit-glsl.tape-texel row)]
    (string.format "texelFetch(%s, ivec2(%d, %d), 0)" name x y)))

(local texel-swizzles {:float ".x" :vec2 ".xy" :vec3 ".xyz" :vec4 "" :int ".x"})

(fn texel-read [texture texel ty]
  ;; A value of type `ty` read from texel `texel` of the rows' texture.
  (let [fetch (.. (row-fetch texture texel) (. texel-swizzles ty))]
    (if (= ty :int) (.. "int(" fetch ")") fetch)))

(fn load-once [declarations code rows-read declaration-text ?varyings? ?tape-texture? ?texels]
  "The shader's body: `declarations` (items from emit-glsl.declare or a chunk's
uniform lines, in order, each written by `declaration-text`) first, then the lines
`code`, each uniform read through a
global copy that loadUniforms(), called first by every entry point, fills. The copy
gName of uName is declared after it and `#define uName gName` renames every read of
the code that follows, the preprocessor's doing: no generated line is rewritten.
Not copied: samplers, the resolution, arrays that code indexes by a variable (their
:loop?). Of the tape's rows only those the code reads (`rows-read`). With
`?varyings?` (LÖVE's entry) as many copies as fit in flat varyings come from a
vertex stage of their own: returns the lines and the vertex stage's. With
`?tape-texture?` the tape's rows (a declaration marked :rows?, written as declared)
are a texture of that name, each row read by one texelFetch (emit-glsl.tape-texel),
and `?texels` (name -> texel) places other uniforms' values in it after the rows
(plan.texels, uniforms.texel-layout): a copy that no varying carries is read from
its texel, not from the uniform (the vertex stage still reads the uniform)."
  (let [out []
        copied []
        reads []
        texture (when ?tape-texture?
                  (accumulate [name nil _ {:declare d} (ipairs declarations)]
                    (or name (when (and d.rows? (= (declaration-text d) d.text)) d.name))))
        texel-of (fn [d i] (case (and texture (?. ?texels d.name))
                             base (texel-read texture (+ base i) d.type)))]
    (var opaque? false)
    (each [_ {:declare d} (ipairs declarations)]
      ;; Unless the caller writes the rows otherwise (the export: as constants).
      (local texture (when (and ?tape-texture? d.rows? (= (declaration-text d) d.text))
                       (rows-texture-declaration d)))
      (table.insert out (or texture (declaration-text d)))
      (when (not (or (. read-directly d.name) (d.type:find "sampler") d.loop?
                     (: (declaration-text d) :find "^const ")))
        (let [copy (.. "g" (d.name:sub 2))]
          (table.insert copied [d.name copy])
          (table.insert out (.. d.type " " copy (if d.count (.. "[" d.count "]") "") ";"))
          (if d.count
              ;; Only the elements the code reads (a folded tape reads only its
              ;; camera-relative rows).
              (for [i 0 (- d.count 1)]
                (when (or (not d.rows?) (. rows-read i))
                  (table.insert reads {:copy (string.format "%s[%d]" copy i) :ty d.type
                                       :uniform d.name
                                       :declaration (or texture d.text)
                                       :read (if texture (row-fetch d.name i)
                                                 (string.format "%s[%d]" d.name i))
                                       :texel (texel-of d i)})))
              (table.insert reads {: copy :ty d.type :uniform d.name :declaration d.text
                                   :read d.name :texel (texel-of d 0)})))))
    (table.insert out "")
    (table.insert out "// Every read of a uniform below is of its copy (see load-once in src/render/codegen.fnl).")
    (each [_ [name copy] (ipairs copied)] (table.insert out (.. "#define " name " " copy)))
    (each [_ line (ipairs code)] (table.insert out line))
    (table.insert out "")
    (each [_ [name] (ipairs copied)] (table.insert out (.. "#undef " name)))
    (local (instead vertex-lines) (if ?varyings? (pack-varyings reads) {}))
    (local copies
      (icollect [_ {: copy : ty : read : texel} (ipairs reads)]
        (let [wrap (. opaque-types ty)
              source (or (. instead read) texel read)]
          (when (and wrap (wrap:find "opaque")) (set opaque? true))
          (string.format "    %s = %s;" copy (if wrap (string.format wrap source) source)))))
    (table.insert out "// Every uniform copied once per pixel (see load-once in src/render/codegen.fnl).")
    (table.insert out "void loadUniforms() {")
    (table.insert out "    // Through values the compiler cannot fold (see load-once in codegen.fnl).")
    (table.insert out (.. "    float nothing = " nothing ";"))
    (table.insert out "    gZero = int(nothing);")
    (when opaque? (table.insert out "    int opaque = 2147483647 - int(nothing);"))
    (each [_ c (ipairs copies)] (table.insert out c))
    (table.insert out "}")
    (values out
            (when vertex-lines
              ;; The uniforms the vertex stage reads, declared there as well (a
              ;; uniform of both stages is one uniform).
              (let [used {}
                    vertex ["// Uniforms read once per vertex, not per pixel (see pack-varyings in"
                            "// src/render/codegen.fnl): flat varyings reach each pixel as broadcasts."]]
                (each [_ {: uniform : read : declaration} (ipairs reads)]
                  (when (and (. instead read) (not (. used uniform)))
                    (tset used uniform true)
                    (table.insert vertex declaration)))
                (for [i 0 (- (length vertex-lines) 1)]
                  (table.insert vertex (.. "flat out vec4 vLoad" i ";")))
                (table.insert vertex "vec4 position(mat4 transform_projection, vec4 vertex_position) {")
                (each [_ l (ipairs vertex-lines)] (table.insert vertex l))
                (table.insert vertex "    return transform_projection * vertex_position;")
                (table.insert vertex "}")
                {:vertex vertex :count (length vertex-lines)})))))

(fn texel-rows [plan]
  ;; name -> the texel of its first element in the rows' texture: plan.texels in
  ;; order after the tape's rows (uniforms.pack writes them so).
  (let [rows {}]
    (var next (length plan.tape.rows))
    (each [_ {: name : count} (ipairs (or plan.texels []))]
      (tset rows name next)
      (set next (+ next (or count 1))))
    rows))

(fn generate [plan target declaration-text]
  (let [body []
        out []
        sections []
        ;; The emitters' context for this shader: which tape rows its code reads.
        cx (emit-glsl.new-context)
        text-of (fn [line] (if (= (type line) :table) (declaration-text line.declare) line))]
    (flatten-into out "" target.header)
    (when (> (length target.header) 0) (table.insert out ""))
    (table.insert out (.. "// Generated by src/render/codegen.fnl for: " plan.key))
    (table.insert out "")
    (each [_ s (ipairs (body-lines cx plan))] (table.insert sections s))
    (each [i s (ipairs sections)]
      (when (> i 1) (table.insert body ""))
      (flatten-into body "" s))
    ;; Every uniform is declared first, where the chunks and the plan declared them.
    (let [declarations (icollect [_ l (ipairs body)] (when (= (type l) :table) l))
          code (icollect [_ l (ipairs body)] (when (= (type l) :string) l))
          (lines vertex) (if plan.load-once? (load-once declarations code (emit-glsl.reads cx)
                                                        declaration-text target.varyings?
                                                        plan.tape-texture? (texel-rows plan))
                             (doto (icollect [_ d (ipairs declarations)] (declaration-text d.declare))
                               (table.insert "")
                               (flatten-into "" code)
                               (table.insert "")
                               (table.insert (.. "void loadUniforms() { gZero = int(" nothing "); }"))))]
      ;; With a vertex stage the pixel stage's code goes under PIXEL (LÖVE compiles
      ;; the text once per stage, defining VERTEX or PIXEL).
      (when vertex
        (table.insert out "#ifdef VERTEX")
        (flatten-into out "" vertex.vertex)
        (table.insert out "#else")
        (for [i 0 (- vertex.count 1)]
          (table.insert out (.. "flat in vec4 vLoad" i ";"))))
      (flatten-into out "" lines)
      (table.insert out "")
      (each [_ l (ipairs (fill target.entry
                               {:mirror [(.. "float mirror = " (if plan.mirrors? "gMirror" "1.0") ";")
                                         "return uProbeChannel == 0 ? vec4(d, color) : vec4(mirror, 0.0, 0.0, 1.0);"]}))]
        (table.insert out (text-of l)))
      (when vertex (table.insert out "#endif")))
    (.. (table.concat out "\n") "\n")))

(fn shader [plan ?target ?declaration]
  "GLSL fragment shader text for `plan`. `?target` is :love (default: LÖVE's effect()
entry point, the uniforms read once handed to pixels in flat varyings; :love-uniforms
reads them from the uniforms instead), :core (a plain #version 330 core shader, for
headless tests and glslangValidator) or :probe (LÖVE, one scene evaluation per pixel; see --probe). `?declaration` (fn [d]) -> text writes each uniform's
declaration (d: {:type :name :count :trailer :text}; the Shadertoy export writes
constants). Returns the text, or nil and a message when a chunk cannot be read."
  (let [target (. targets (or ?target :love))
        _ (assert target (.. "unknown target " (tostring ?target)))
        declaration (or ?declaration default-declaration)
        ;; A folded plan's settings are constants (plan :baked).
        (ok? result) (pcall generate plan target
                            (if plan.baked
                                (fn [d] (case (. plan.baked d.name)
                                          text (.. text d.trailer)
                                          _ (declaration d)))
                                declaration))]
    (if ok? result
        (chunk-error? result) (values nil result.message)
        (error result 0))))

{: shader : set-reader!}

;; Uniform values for a plan: the scene and the camera become a list of uniforms with
;; flat number lists. Positions are made camera-relative here, in double precision,
;; before they are rounded to float32 on upload.

(local camera (require :src.render.camera))
(local large-sphere (require :src.sdf.large-sphere))
(local bounds (require :src.render.bounds))
(local strategies (require :src.sdf.strategies))
(local features (require :src.render.features))
(local emit-glsl (require :src.sdf.emit-glsl))

(fn hit-threshold [scene plan cam height]
  "The shader's hitThreshold on the CPU: a step under this at `dist` from the camera
is a hit (see shaders/pipeline/hit/)."
  (let [eps scene.render.epsilon]
    (case plan.hit-test
      :fixed (fn [_] eps)
      :relative (fn [dist] (* eps dist))
      :pixel (let [k (/ eps (* (camera.projection-distance cam) height))]
               (fn [dist] (* k dist))))))

(local components {:float 1 :int 1 :bool 1 :vec2 2 :vec3 3 :vec4 4})
(local texel-types {:float true :int true :vec2 true :vec3 true :vec4 true})

(fn texel-values [out texels]
  ;; The values of `texels` (plan.texels) taken from pack's uniforms `out`: each
  ;; element a texel, its components first, zeros after.
  (let [by-name (collect [_ u (ipairs out)] u.name u)
        vals []]
    (each [_ {: name : type : count} (ipairs texels)]
      (let [u (. by-name name)
            n (. components type)]
        (for [e 0 (- (or count 1) 1)]
          (for [k 1 4]
            (table.insert vals (or (and u (<= k n) (. u.values (+ (* e n) k))) 0))))))
    vals))

(fn relative [[x y z] [cx cy cz]]
  [(- x cx) (- y cy) (- z cz)])

(fn append! [out vs]
  (each [_ v (ipairs vs)] (table.insert out v))
  out)

(fn tape-values [tape cam]
  "The rows of `tape` (or of its instance groups' bank, which has the same fields) as
one flat list; rows holding a world position (each object's outermost translation)
are made camera-relative here, in double. An object that takes the camera off one
level in (:inner, see src/sdf/lower.fnl's hand-in) gets a translation of 0, each
translation reading it T + t - camera and each plane reading it the height
h + dot(n, T - camera): the shader's point stays near the camera, not the world
point rounded to float32. A derived row (a large sphere's k) is computed from its
centre's row and the camera."
  (let [[cx cy cz] cam
        relative (collect [_ r (ipairs tape.relative)] r true)
        ;; Row index (0-based) -> the values sent for it.
        instead {}
        _ (each [_ {: root : translations : planes} (ipairs (or tape.inner []))]
            (let [[tx ty tz w] (. tape.rows (+ root 1))
                  dx (- tx cx) dy (- ty cy) dz (- tz cz)]
              (tset instead root [0 0 0 w])
              (each [_ r (ipairs translations)]
                (let [[x y z w] (. tape.rows (+ r 1))]
                  (tset instead r [(+ x dx) (+ y dy) (+ z dz) w])))
              (each [_ {: row} (ipairs planes)]
                (let [[x y z w] (. tape.rows (+ row 1))]
                  (tset instead row [x y z (+ w (* x dx) (* y dy) (* z dz))])))))
        _ (each [_ {: row : centre} (ipairs (or tape.derived []))]
            (let [[x y z r] (. tape.rows (+ centre 1))]
              (tset instead row [(large-sphere.k [x y z] r cam) 0 0 0])))
        out []]
    (each [i row (ipairs tape.rows)]
      (let [[x y z w] row]
        (if (. instead (- i 1)) (append! out (. instead (- i 1)))
            (. relative (- i 1)) (append! out [(- x cx) (- y cy) (- z cz) w])
            (append! out [x y z w]))))
    out))

(local {: linear} (require :src.render.color))

(fn lighting-uniforms [lighting plan cam-pos]
  "The modern model's uniforms (see src/render/codegen.fnl)."
  (let [positions []
        colors []
        out []
        sun (* (/ lighting.sun-size 180) math.pi)]
    (each [_ l (ipairs lighting.lights)]
      (if (= l.kind :sun)
          (append! positions [(. l.direction 1) (. l.direction 2) (. l.direction 3) 0])
          (append! positions (doto (relative l.pos cam-pos) (table.insert l.range))))
      (append! colors (doto (linear l.color l.intensity) (table.insert l.softness))))
    (append! out
             [{:name "uLights" :type :vec4 :values positions :count (length lighting.lights)
               ;; A point light's position is camera-relative.
               :view? (accumulate [point? false _ l (ipairs lighting.lights)]
                        (or point? (not= l.kind :sun)))}
              {:name "uLightColors" :type :vec4 :values colors :count (length lighting.lights)}
              {:name "uSkyZenith" :type :vec3 :values (linear lighting.sky-zenith)}
              {:name "uSkyHorizon" :type :vec3 :values (linear lighting.sky-horizon)}
              ;; No disc: cosines above 1, where smoothstep gives 0.
              {:name "uSunEdge" :type :vec2 :values (if (> sun 0) [(math.cos sun) (math.cos (* 0.8 sun))]
                                                        [2 3])}
              {:name "uAmbient" :type :float :values [lighting.ambient]}
              {:name "uExposure" :type :float :values [lighting.exposure]}])
    (each [_ name (ipairs plan.lighting.features)]
      (append! out ((. (features.lookup name) :uniforms) lighting cam-pos)))
    out))

(fn grid-uniforms [grids cam-pos]
  "The uniforms of a plan's grids (src/sdf/grid.fnl, src/render/plan.fnl's grids-of):
per grid its low corner about the anchor, reach, cell, first cell and cells along
each axis; the anchor camera-relative (in double); the textures (the same tables
every frame, so a backend uploads them once) and their rows' reciprocals."
  (let [{: list : anchor : textures} grids
        [ax ay az] anchor
        rows []]
    (each [i {: grid : blend?} (ipairs list)]
      ;; A group's grid is about the anchor, a blend's in its own point's frame.
      (let [[ax ay az] (if blend? [0 0 0] anchor)
            [lx ly lz] grid.lo
            [cx cy cz] grid.cell
            [nx ny nz] grid.dims]
        (append! rows [(- lx ax) (- ly ay) (- lz az) grid.reach
                       cx cy cz (. textures.offsets i :cell)
                       nx ny nz 0])))
    [{:name "uGrids" :type :vec4 :count (* 3 (length list)) :values rows}
     {:name "uBankOrigin" :type :vec3 :values (relative anchor cam-pos) :view? true}
     {:name "uGridRows" :type :vec4 :values [(/ 1 textures.bank.height) (/ 1 textures.cells.height)
                                            (/ 1 textures.lists.height) (/ 1 textures.spheres.height)]}
     {:name "uGridSpheres" :type :texture :texture textures.spheres}
     {:name "uGridFirsts" :type :texture :texture textures.firsts}
     {:name "uGridFirstRows" :type :float :values [(/ 1 textures.firsts.height)]}
     {:name "uBankRows" :type :texture :texture textures.bank}
     {:name "uGridCells" :type :texture :texture textures.cells}
     {:name "uGridLists" :type :texture :texture textures.lists}]))

(fn pack [scene plan cam width height]
  "Uniforms for drawing `scene` lowered to `plan`, seen by camera state `cam`, into a
`width` x `height` target: a list of {:name :type :values [numbers] :count n} sorted
by name. Booleans are sent as 0 or 1 with :type :bool. A field's textures come as
{:name :type :texture :texture {:width :height :data}} (no :values). A uniform whose
values follow the view (the camera, the target's size: camera-relative positions) is
marked :view? true; the others are the scene's settings (see fixed)."
  (let [(f r u) (camera.basis cam)
        render scene.render
        out [{:name "uResolution" :type :vec2 :values [width height] :view? true}
             {:name "uCamForward" :type :vec3 :values f :view? true}
             {:name "uCamRight" :type :vec3 :values r :view? true}
             {:name "uCamUp" :type :vec3 :values u :view? true}
             {:name "uProjDist" :type :float :values [(camera.projection-distance cam)] :view? true}
             {:name "uLightPos" :type :vec3 :values (relative scene.light.pos cam.pos) :view? true}
             {:name "uEnvColor" :type :vec3 :values scene.environment}
             {:name "uMaxSteps" :type :int :values [render.max-steps]}
             {:name "uEpsilon" :type :float :values [render.epsilon]}
             {:name "uDrawDist" :type :float :values [render.draw-distance]}]]
    (when plan.reflections?
      (table.insert out {:name "uReflections" :type :int :values [plan.reflections]}))
    (when plan.relaxed?
      (table.insert out {:name "uRelaxation" :type :float :values [render.relaxation]}))
    (when plan.uber?
      (table.insert out {:name "uShadows" :type :bool :values [(if render.shadows 1 0)]})
      (table.insert out {:name "uGlow" :type :bool :values [(if render.glow 1 0)]}))
    (when plan.lighting
      (append! out (lighting-uniforms scene.lighting plan cam.pos)))
    ;; A strategy's own (a field's grid and textures): taken as the view's.
    (each [_ o (ipairs plan.tape.objects)]
      (case (. (strategies.of o) :uniforms)
        f (each [_ u (ipairs (f plan o cam.pos))]
            (set u.view? true)
            (table.insert out u))))
    (when plan.grids
      (append! out (grid-uniforms plan.grids cam.pos)))
    (var tape-rows nil)
    (each [_ [name bank] (ipairs [["uTape" plan.tape] ["uInstances" plan.tape.instances]])]
      (when (and (> (length bank.rows) 0) (not bank.texture?))
        (let [vals (tape-values bank cam.pos)
              rows (length bank.rows)]
          (if (and plan.tape-texture? (= bank plan.tape))
              (set tape-rows vals)
              (table.insert out {: name :type :vec4 :values vals :count rows :view? true})))))
    (when (bounds.others? plan)
      (let [flat (bounds.spheres plan cam.pos (hit-threshold scene plan cam height))]
        (table.insert out (if plan.bounds.texture?
                              ;; Their count with them (the interpreter's: not in the text).
                              {:name "uBounds" :type :texture :view? true
                               :texture (bounds.texture flat)}
                              {:name "uBounds" :type :vec4 :count plan.bounds.count :view? true
                               :values flat}))))
    (when tape-rows
      ;; A row a texel (codegen's load-once, emit-glsl.tape-texel), then the texels of
      ;; the plan's :texels.
      (let [vals (append! tape-rows (texel-values out (or plan.texels [])))
            texels (/ (length vals) 4)]
        (table.insert out {:name "uTape" :type :texture :count texels :view? true
                           :texture {:width (math.min texels emit-glsl.tape-texture-width)
                                     :height (math.ceil (/ texels emit-glsl.tape-texture-width))
                                     :data vals}})))
    (table.sort out (fn [a b] (< a.name b.name)))
    out))

(fn texel-value? [u]
  ;; Whether uniform `u` of pack's list may ride a texel: numbers of a float or int
  ;; type, alone or in an array that load-once copies (emit-glsl.max-copied-array),
  ;; not the target's size (read where used).
  (and (not= nil u.values) (. texel-types u.type) (not= u.name "uResolution")
       (or (= nil u.count) (<= u.count emit-glsl.max-copied-array))))

(fn texel-layout [scene plan]
  "The values that ride the tape's texture after its rows, on a plan whose rows do
(:tape-texture?): [{:name :type :count}], pack's uniforms that may (not baked into
the code), in pack's order, a texel for each element. Codegen's load-once reads a
value there when no flat varying carries it (llvmpipe compiles a texel fetch
quicker than a uniform read); pack writes them. Names and counts only, never
values: a value edit keeps the layout, and the shader."
  (icollect [_ u (ipairs (pack scene plan (camera.from-scene scene) 1 1))]
    (when (and (texel-value? u) (= nil (?. plan :baked u.name)))
      {:name u.name :type u.type :count u.count})))

(fn prior [pass ?image]
  "The uniforms of an adaptive plan's picture of centre rays (shaders/pipeline/
adaptive.glsl): `pass` 1 draws it, 2 reads it from `?image` (the renderer's own
image of it, sent as it is: {:name :type :image}). An adaptive plan drawn without
these has none (pass 0), as the CPU reference draws it."
  (if (= pass 2)
      [{:name "uPriorPass" :type :float :values [2]} {:name "uPrior" :type :image :image ?image}]
      [{:name "uPriorPass" :type :float :values [pass]}]))

(fn fixed [scene plan]
  "The uniforms of `scene` lowered to `plan` that no view changes (pack's without
:view?, textures aside): the render settings, the lighting model's values, a sun's
direction. The folded shader writes them as constants (plan :baked)."
  (icollect [_ u (ipairs (pack scene plan (camera.from-scene scene) 1 1))]
    (when (and (not u.view?) u.values) u)))

(local float-literal emit-glsl.float-literal)

(fn value-literal [kind vals i]
  (let [n (. components kind)]
    (case kind
      :float (float-literal (. vals i))
      :int (string.format "%d" (. vals i))
      :bool (if (= 0 (. vals i)) "false" "true")
      _ (.. kind "(" (table.concat (fcollect [k 0 (- n 1)] (float-literal (. vals (+ i k)))) ", ")
            ")"))))

(fn constant [u]
  "The GLSL declaration of uniform `u` (an item of pack's list) as a constant of its
values: `const vec3 uName = vec3(...);`, an array as an array constructor."
  (let [n (. components u.type)]
    (if u.count
        (.. "const " u.type " " u.name "[" u.count "] = " u.type "[" u.count "]("
            (table.concat (fcollect [e 0 (- u.count 1)] (value-literal u.type u.values (+ 1 (* e n))))
                          ", ")
            ");")
        (.. "const " u.type " " u.name " = " (value-literal u.type u.values 1) ";"))))

{: pack : fixed : constant : prior : components : linear : tape-values : texel-layout}

;; Stress scenes (scenes/stress/*.fnl): extreme cameras, sizes, distances and settings,
;; each rendered small by the generated GLSL through OSMesa on a float target and traced
;; by the CPU reference marcher on sampled pixels. For every scene in the folder:
;;   finite    no NaN or Inf in the GPU's shaded, normals and heat images (float target,
;;             raw values) nor in the reference's colours, distances and lightness
;;   agree     GPU against reference on the sampled pixels, shaded and normals views,
;;             within the scene's budget (over = pixels whose largest channel differs by
;;             more than 2/255, max in 0..255 units)
;;   steps     the reference's primary-ray steps never above :max-steps on a sampled
;;             pixel, and the GPU's step count (decoded exactly from the float heat
;;             view) within 2 of the reference's on every sampled pixel but :steps-off
;;             of them (default 0). The heat view clamps at 1, so it cannot itself show a
;;             count above the limit; the agreement with the reference shows it.
;;   stable    the camera nudged by 1e-6 along x, y and z in turn and re-rendered on the
;;             GPU: pixels whose largest channel moves by more than 2/255, the worst
;;             axis, within the scene's budget
;; One line of figures per scene is printed.

;; Budgets, measured on llvmpipe (Mesa 22.3, LLVM 15) at 96x64 (tall-window: 1x1000),
;; the harness's sampling ({:grid 16 :extra 256 :step 4 :seed 1}), with the render
;; defaults of this tree (relative hit test, epsilon 1e-4, tetrahedron normals,
;; relaxation 1.5, 500 steps). :shaded and :normals are {:over :max} (over = sampled
;; pixels above 2/255, max in 0..255 units; the float target is compared unrounded, so
;; llvmpipe's exact agreement shows as max 0.0-0.4; a max budget is the measured max
;; rounded up to the next 0.5). :stable is the worst axis's count of pixels moved by a
;; 1e-6 nudge (the ceiling: 0.5% of the image or 8, whichever is larger: 30 at 96x64).
;; :pending holds a check that fails because of a renderer problem, with its figures.
(local exact {:over 0 :max 0.5})   ; measured over 0, max 0.0-0.4

(local budgets
  {;; Ties go to the first object in plan order on both sides: no speckle.
   "scenes/stress/coincident.fnl" {:shaded exact :normals exact :stable 0}
   ;; All sky in one step.
   "scenes/stress/draw-distance-short.fnl" {:shaded exact :normals exact :stable 0}
   ;; Epsilon 0: 93% of the pixels spend all 500 steps converging. Measured over 9,
   ;; max 64.1, all in sphere-ground-sphere bounce chains in the crevice where the
   ;; sphere touches the ground, whose secondary marches also run out of steps and end
   ;; wherever rounding leaves them; the same chains move 15 pixels under a nudge. The
   ;; fixed and relative hit tests are the same test at epsilon 0: same figures.
   ;; Primary rays that never converge stop where float32 leaves them: 17 sampled
   ;; pixels end with step counts more than 2 away from the reference's.
   "scenes/stress/epsilon-zero-fixed.fnl" {:shaded {:over 9 :max 64.5}
                                           :normals {:over 0 :max 2} ; measured max 1.7
                                           :stable 15 :steps-off 17}
   "scenes/stress/epsilon-zero-relative.fnl" {:shaded {:over 9 :max 64.5}
                                              :normals {:over 0 :max 2} ; measured max 1.7
                                              :stable 15 :steps-off 17}
   ;; Camera-relative positions in double: as exact as at the origin.
   "scenes/stress/far-origin.fnl" {:shaded exact :normals exact :stable 0}
   "scenes/stress/fov-narrow.fnl" {:shaded exact :normals exact :stable 0}
   "scenes/stress/fov-wide.fnl" {:shaded exact :normals exact :stable 0}
   ;; 6.0% of the image at the step limit (4.5-4.6% with the defaults), yet the GPU
   ;; matches: both stop on the same step.
   "scenes/stress/grazing-horizon-article.fnl" {:shaded exact :normals exact :stable 0}
   ;; One horizon pixel flips under a nudge.
   "scenes/stress/grazing-horizon-down.fnl" {:shaded exact :normals exact :stable 1}
   "scenes/stress/grazing-horizon.fnl" {:shaded exact :normals exact :stable 0}
   ;; Inside the box the first step is the hit, behind the camera, and the normal comes
   ;; from the interior distance, whose gradient jumps across the box's inner
   ;; diagonals: measured 1 pixel over (max 10.0) on a diagonal, 5 moved by a nudge.
   "scenes/stress/inside-box.fnl" {:shaded {:over 1 :max 10} :normals exact :stable 5}
   "scenes/stress/inside-sphere.fnl" {:shaded exact :normals exact :stable 0}
   "scenes/stress/light-inside.fnl" {:shaded exact :normals exact :stable 0}
   "scenes/stress/light-on-surface.fnl" {:shaded exact :normals exact :stable 0}
   ;; One step per ray: mid-air points coloured by the nearest object, whose colour
   ;; changes where two objects are equally near: measured 1 over (max 4.5), and 7
   ;; pixels on those borders move under a nudge.
   "scenes/stress/max-steps-one.fnl" {:shaded {:over 1 :max 4.5} :normals exact :stable 7}
   ;; 10 bounces between parallel mirrors: still exact. With bounds (issue 11) one
   ;; pixel moves under a nudge: a tenth bounce that grazes a mirror's bounding sphere.
   "scenes/stress/mirrors.fnl" {:shaded exact :normals exact :stable 1}
   ;; One silhouette pixel moves under a nudge.
   "scenes/stress/pitch-down.fnl" {:shaded exact :normals exact :stable 1}
   "scenes/stress/pitch-up.fnl" {:shaded exact :normals exact :stable 0}
   ;; A radius-1e6 planet seen from 0.25 above its surface. Before large spheres got
   ;; their cancellation-free distance (shaders/sdf/large-sphere.glsl) the float32
   ;; length(p - c) - r was only good to ~0.06 here, far more than the offset of
   ;; shadow and mirror rays: they hit the ground they left, and the GPU image came
   ;; out shadowed and self-reflecting (200 of 406 sampled pixels over, max 128.2/255,
   ;; e.g. pixel (90, 60) gpu [0.072 0.143 0.083] cpu [0.524 0.634 0.585]). Now it
   ;; matches the reference exactly (0 over, max 0.0; stable 0).
   "scenes/stress/planet.fnl" {:shaded exact :normals exact :stable 0}
   "scenes/stress/tall-window.fnl" {:shaded exact :normals exact :stable 0}
   "scenes/stress/thin-box.fnl" {:shaded exact :normals exact :stable 0}
   ;; The article's settings: the GPU matches, but the fixed hit test as large as the
   ;; objects makes their swollen silhouettes and mirror images sensitive to the
   ;; camera: 61 pixels move under a 1e-6 nudge (above the 30-pixel ceiling; that is
   ;; the problem this variant shows, against 24 with the defaults).
   "scenes/stress/tiny-objects-article.fnl" {:shaded exact :normals exact :stable 61}
   ;; A 1e-6 nudge is 0.1% of this scene's size (1e-3): the tiny sphere's reflections
   ;; move: measured 24 pixels (worst axis); 26 with bounds (issue 11), whose span
   ;; starts the march at a sphere 1e-3 across instead of at the camera.
   "scenes/stress/tiny-objects.fnl" {:shaded exact :normals exact :stable 26}})

;; Scenes not rendered at the default size.
(local sizes {"scenes/stress/tall-window.fnl" [1 1000]})
(local default-size [96 64])
(local sample-options {:grid 16 :extra 256 :step 4 :seed 1})
(local nudge 1e-6)

(local headless (require :src.backend.headless))
(local scene-loader (require :src.scene.load))
(local plan-mod (require :src.render.plan))
(local camera (require :src.render.camera))
(local codegen (require :src.render.codegen))
(local uniforms (require :src.render.uniforms))
(local reference (require :src.reference))
(local compare (require :src.verify.compare))
(local {: heat->fraction} (require :src.verify.report))
(local {: scene-files : tolerance} (require :test.support.gpu-check))

(fn finite? [v]
  (and (= (type v) :number) (= v v) (not= v math.huge) (not= v (- math.huge))))

(fn clamp01 [v] (if (< v 0) 0 (> v 1) 1 v))

(fn plan-for [s view]
  (let [(p err) (plan-mod.scene->plan s {: view})]
    (assert p err)
    p))

(fn render-float [ctx program s p cam width height]
  (let [(image err) (headless.render ctx program {: width : height :float? true
                                                  :uniforms (uniforms.pack s p cam width height)})]
    (assert image err)
    image))

(fn non-finite-pixels [image]
  "Pixels of a float image with a NaN or infinite channel (r, g or b)."
  (var n 0)
  (for [y 0 (- image.height 1)]
    (for [x 0 (- image.width 1)]
      (let [(r g b) (headless.pixel image x y)]
        (when (not (and (finite? r) (finite? g) (finite? b)))
          (set n (+ n 1))))))
  n)

(fn gpu-vs-cpu [image expected]
  "Stats of the float GPU image (clamped as an 8-bit target would) against the
reference results, in 0..255 units; a non-finite GPU pixel counts as 255."
  (let [diffs (icollect [_ r (ipairs expected)]
                (let [gpu [(headless.pixel image r.x r.y)]
                      ok? (and (finite? (. gpu 1)) (finite? (. gpu 2)) (finite? (. gpu 3)))]
                  (if ok?
                      (compare.pixel-diff (icollect [i g (ipairs gpu) &until (> i 3)]
                                            (* 255 (clamp01 g)))
                                          (icollect [_ c (ipairs r.color)] (* 255 c)))
                      255)))]
    (compare.stats diffs tolerance)))

(fn moved-pixels [a b]
  "Pixels whose largest channel differs by more than 2/255 between two float images
(a NaN on either side counts as moved)."
  (var n 0)
  (for [y 0 (- a.height 1)]
    (for [x 0 (- a.width 1)]
      (let [(ar ag ab) (headless.pixel a x y)
            (br bg bb) (headless.pixel b x y)
            d (math.max (math.abs (- (clamp01 ar) (clamp01 br)))
                        (math.abs (- (clamp01 ag) (clamp01 bg)))
                        (math.abs (- (clamp01 ab) (clamp01 bb))))]
        (when (not (<= d (/ tolerance 255))) (set n (+ n 1))))))
  n)

(fn reference-non-finite [results]
  (var n 0)
  (each [_ r (ipairs results)]
    (let [[cr cg cb] r.color]
      (when (not (and (finite? cr) (finite? cg) (finite? cb) (finite? r.distance)
                      (finite? r.steps) (or (= r.lightness nil) (finite? r.lightness))))
        (set n (+ n 1)))))
  n)

(fn measure [ctx file]
  "Every figure of one stress scene."
  (let [[width height] (or (. sizes file) default-size)
        (s err) (scene-loader.load-file file)
        _ (assert s err)
        cam (camera.from-scene s)
        max-steps s.render.max-steps
        views {}
        out {: file :name s.name : width : height : max-steps}]
    (each [_ view (ipairs [:shaded :normals :heat])]
      (let [p (plan-for s view)
            (program cerr) (headless.compile ctx (codegen.shader p :core))]
        (assert program cerr)
        (tset views view {: p : program})))
    ;; Reference on sampled pixels (chosen on the shaded view), shaded and normals.
    (let [shaded views.shaded.p
          pixels (compare.sample-pixels s shaded cam width height sample-options)
          ref-shaded (reference.render-pixels s shaded cam width height pixels)
          ref-normals (reference.render-pixels s views.normals.p cam width height pixels)]
      (set out.samples (length pixels))
      (set out.ref-non-finite (+ (reference-non-finite ref-shaded)
                                 (reference-non-finite ref-normals)))
      (set out.ref-max-steps (accumulate [m 0 _ r (ipairs ref-shaded)] (math.max m r.steps)))
      (let [img-shaded (render-float ctx views.shaded.program s shaded cam width height)
            img-normals (render-float ctx views.normals.program s views.normals.p cam width height)
            img-heat (render-float ctx views.heat.program s views.heat.p cam width height)]
        (set out.gpu-non-finite {:shaded (non-finite-pixels img-shaded)
                                 :normals (non-finite-pixels img-normals)
                                 :heat (non-finite-pixels img-heat)})
        (set out.shaded (gpu-vs-cpu img-shaded ref-shaded))
        (set out.normals (gpu-vs-cpu img-normals ref-normals))
        ;; Heat: steps / max-steps, decoded; NaN compares false and counts as over.
        (var hmax 0)
        (var hbad 0)
        (for [y 0 (- height 1)]
          (for [x 0 (- width 1)]
            (let [(r g b) (headless.pixel img-heat x y)
                  h (heat->fraction r g b)]
              (if (not (<= h (+ 1 1e-6))) (set hbad (+ hbad 1))
                  (> h hmax) (set hmax h)))))
        (set out.gpu-heat-max hmax)
        (set out.gpu-heat-full (accumulate [n 0 _ y (ipairs (fcollect [y 0 (- height 1)] y))]
                                 (+ n (accumulate [k 0 _ x (ipairs (fcollect [x 0 (- width 1)] x))]
                                        (if (>= (heat->fraction (headless.pixel img-heat x y))
                                                (- 1 1e-6))
                                            (+ k 1) k)))))
        (set out.gpu-heat-over hbad)
        ;; The heat view clamps at 1, so it cannot show a count above the limit; what
        ;; it can show is whether the GPU's march takes the reference's number of steps.
        (set out.steps-off
             (accumulate [n 0 _ r (ipairs ref-shaded)]
               (let [gpu-steps (* max-steps (heat->fraction (headless.pixel img-heat r.x r.y)))]
                 (if (> (math.abs (- gpu-steps r.steps)) 2) (+ n 1) n))))
        ;; Stability: nudge the camera along each axis.
        (set out.stable 0)
        (set out.nudged-non-finite 0)
        (for [axis 1 3]
          (let [moved (camera.from-scene s)]
            (tset moved.pos axis (+ (. moved.pos axis) nudge))
            (let [img (render-float ctx views.shaded.program s shaded moved width height)]
              (set out.nudged-non-finite (+ out.nudged-non-finite (non-finite-pixels img)))
              (set out.stable (math.max out.stable (moved-pixels img-shaded img))))))))
    (each [_ v (pairs views)] (headless.release ctx v.program))
    out))

(fn figures-line [m]
  (string.format "stress %-34s %4dx%-4d samples %3d  nan gpu %d/%d/%d ref %d  shaded over %3d max %5.1f  normals over %3d max %5.1f  steps ref %d/%d gpu h %.3f (%4.1f%% at 1) off %d  stable %d"
                 (m.file:match "([^/]+)%.fnl$") m.width m.height m.samples
                 m.gpu-non-finite.shaded m.gpu-non-finite.normals m.gpu-non-finite.heat
                 m.ref-non-finite m.shaded.over m.shaded.max m.normals.over m.normals.max
                 m.ref-max-steps m.max-steps m.gpu-heat-max
                 (/ (* 100 m.gpu-heat-full) (* m.width m.height)) m.steps-off m.stable))

(fn within? [st b]
  (and (<= st.over b.over) (<= st.max b.max)))

(describe "stress scenes, GPU against the CPU reference"
  (fn []
    (let [(ctx why) (headless.context)
          files (scene-files "scenes/stress")
          cache {}
          measured (fn [file]
                     (when (= nil (. cache file))
                       (let [m (measure ctx file)]
                         (print (figures-line m))
                         (tset cache file m)))
                     (. cache file))]
      (it "finds at least 14 stress scenes, each with a measured budget"
        (fn []
          (assert.is_true (>= (length files) 14) (.. (length files) " scenes"))
          (each [_ file (ipairs files)]
            (assert.is_truthy (. budgets file) (.. file ": no budget measured yet")))))
      (if (not ctx)
          (pending (.. "OSMesa is not available: " (tostring why)))
          (each [_ file (ipairs files)]
            (let [b (or (. budgets file) {})
                  check (fn [what f]
                          (if (?. b :pending what)
                              (pending (.. file ": " what ": " (. b :pending what)))
                              (it (.. file ": " what)
                                (fn []
                                  (let [m (measured file)]
                                    (f m (.. file ": " what ": " (figures-line m))))))))]
              (check "no NaN or Inf"
                     (fn [m msg]
                       (assert.are.equal 0 m.ref-non-finite msg)
                       (assert.are.same {:shaded 0 :normals 0 :heat 0} m.gpu-non-finite msg)
                       (assert.are.equal 0 m.nudged-non-finite msg)))
              (check "steps within the limit"
                     (fn [m msg]
                       (assert.is_true (<= m.ref-max-steps m.max-steps) msg)
                       (assert.are.equal 0 m.gpu-heat-over msg)
                       (assert.is_true (<= m.steps-off (or b.steps-off 0))
                                       (.. msg " (steps-off budget " (or b.steps-off 0) ")"))))
              (check "agrees with the reference"
                     (fn [m msg]
                       (assert.is_truthy b.shaded msg)
                       (assert.is_true (within? m.shaded b.shaded)
                                       (.. msg " (shaded budget " b.shaded.over "/" b.shaded.max ")"))
                       (assert.is_true (within? m.normals b.normals)
                                       (.. msg " (normals budget " b.normals.over "/" b.normals.max ")"))))
              (check "stable under a 1e-6 nudge"
                     (fn [m msg]
                       (assert.is_truthy b.stable msg)
                       (assert.is_true (<= m.stable b.stable) (.. msg " (budget " b.stable ")"))))))))))

(local rad (/ math.pi 180))

(fn article-right [[fx fy fz]]
  "The article's right vector, normalize(cross([0 0 -1], forward)), as
camera.article-basis computes it, for a forward vector given directly."
  (let [[x y z] [(- (* 0 fz) (* -1 fy)) (- (* -1 fx) (* 0 fz)) (- (* 0 fy) (* 0 fx))]
        len (math.sqrt (+ (* x x) (* y y) (* z z)))]
    [(/ x len) (/ y len) (/ z len)]))

(fn all-finite? [vs]
  (accumulate [ok? true _ v (ipairs vs)] (and ok? (finite? v))))

(describe "camera basis looking straight down or up"
  (fn []
    (it "the article's construction is NaN for an exactly vertical forward; camera.basis is finite"
      (fn []
        ;; Exactly vertical forward vectors, built directly: cross([0 0 -1], f) vanishes
        ;; and normalizing it is 0/0.
        (each [_ f (ipairs [[0 0 -1] [0 0 1]])]
          (let [r (article-right f)]
            (assert.is_false (all-finite? r) (.. "article right " (table.concat r " ")))))
        ;; Pitch exactly +-90 through the camera module: the article's construction
        ;; survives in double only because cos(90 degrees) rounds to 6e-17, not 0.
        (assert.is_true (< 0 (math.abs (math.cos (* 90 rad))) 1e-16))
        (each [_ pitch (ipairs [90 -90])]
          (each [_ yaw (ipairs [0 37 90 255])]
            (let [cam {:pos [0 0 0] :yaw yaw :pitch pitch :fov 60}
                  (f r u) (camera.basis cam)
                  (af ar au) (camera.article-basis cam)]
              (assert.is_true (and (all-finite? f) (all-finite? r) (all-finite? u))
                              (.. "basis at pitch " pitch " yaw " yaw))
              ;; Right is (sin yaw, -cos yaw, 0), the article's where that is defined.
              (assert.is_true (< (math.abs (- (. r 1) (math.sin (* yaw rad)))) 1e-12))
              (assert.is_true (< (math.abs (+ (. r 2) (math.cos (* yaw rad)))) 1e-12))
              (assert.are.equal 0 (. r 3))
              (for [i 1 3]
                (assert.is_true (< (math.abs (- (. r i) (. ar i))) 1e-9))
                (assert.is_true (< (math.abs (- (. u i) (. au i))) 1e-9))))))))))

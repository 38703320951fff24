;; Specs for the modern lighting model (issue 10): the :lighting section, the plan's
;; features, the shader holding only what a scene uses, the CPU reference's model,
;; and (through OSMesa) each feature's GLSL against the reference: switched off in the
;; GLSL, the comparison must fail.
(local scene (require :src.scene.load))
(local plan (require :src.render.plan))
(local codegen (require :src.render.codegen))
(local reference (require :src.reference))
(local camera (require :src.render.camera))
(local headless (require :src.backend.headless))
(local {: prepare : gpu-render : compare-image : passes? : describe-failures : report-line}
  (require :test.support.gpu-check))

(fn load [source]
  (let [(s err) (scene.load-string source "t.fnl")]
    (assert s err)
    s))

(fn load-error [source]
  (let [(s err) (scene.load-string source "t.fnl")]
    (assert.is_nil s)
    err))

(fn shader-of [source ?options]
  (assert (codegen.shader (assert (plan.scene->plan (load source) ?options)) :core)))

(local objects ":objects [{:kind :plane :height 0} {:kind :sphere :radius 1 :pos [0 0 1]}]")

(fn modern [lighting ?render]
  (.. "{:lighting " lighting " :render " (or ?render "{}") " " objects "}"))

(describe "lighting: the :lighting section"
  (fn []
    (it "is absent for the classic model, and :model :classic means the same"
      (fn []
        (assert.is_nil (. (load (.. "{" objects "}")) :lighting))
        (assert.is_nil (. (load (modern "{:model :classic}")) :lighting))))

    (it "fills defaults, with one sun from the classic light's direction"
      (fn []
        (let [l (. (load (.. "{:light {:pos [0 0 5]} :lighting {} " objects "}")) :lighting)]
          (assert.are.equal :modern l.model)
          (assert.are.equal 1 (length l.lights))
          (assert.are.equal :sun (. l.lights 1 :kind))
          (assert.are.same [0 0 1] (. l.lights 1 :direction))
          (assert.are.equal 0 l.fog)
          (assert.is_true l.specular))))

    (it "normalises a sun's direction and keeps a point light's position"
      (fn []
        (let [l (. (load (modern "{:lights [{:kind :sun :direction [0 0 3]} {:kind :point :pos [1 2 3]}]}"))
                   :lighting)]
          (assert.are.same [0 0 1] (. l.lights 1 :direction))
          (assert.are.same [1 2 3] (. l.lights 2 :pos))
          (assert.are.equal 10 (. l.lights 2 :range)))))

    (it "names the field in its messages"
      (fn []
        (assert.matches "t.fnl:1: lighting.fgo: unknown field %(did you mean :fog%?%)"
                        (load-error (modern "{:fgo 1}")))
        (assert.matches "lighting.lights%[1%]: missing :kind"
                        (load-error (modern "{:lights [{:pos [1 2 3]}]}")))
        (assert.matches "lighting.lights%[1%].kind: must be one of :point :sun, got :spot"
                        (load-error (modern "{:lights [{:kind :spot}]}")))
        (assert.matches "lighting.lights%[1%].range: unknown field"
                        (load-error (modern "{:lights [{:kind :sun :range 3}]}")))
        (assert.matches "lighting.lights: has 9 lights; at most 8 are allowed %(remove 1%)"
                        (load-error (modern (.. "{:lights [" (string.rep "{:kind :sun} " 9) "]}"))))
        (assert.matches "lighting.ao: must be a number from 0 to 1, got 2"
                        (load-error (modern "{:ao 2}")))
        (assert.matches "lighting.lights%[1%].softness: must be a penumbra width"
                        (load-error (modern "{:lights [{:kind :sun :softness -1}]}")))
        (assert.matches "lighting: must be a table"
                        (load-error (modern "true")))))

    (it "refuses material fields only the modern model reads in a classic scene"
      (fn []
        (assert.matches "objects%[1%].roughness: is read only by the modern lighting model"
                        (load-error "{:objects [{:kind :sphere :radius 1 :roughness 0.5}]}"))
        (assert.matches "objects%[1%].emission: is read only by the modern lighting model"
                        (load-error "{:objects [{:kind :sphere :radius 1 :emission 2}]}"))
        (assert.is_table (load (modern "{}" "{}")))
        (assert.is_table (load "{:lighting {} :objects [{:kind :sphere :radius 1 :emission 2 :roughness 0.1}]}"))))

    (it "lets lights change over time (a value edit)"
      (fn []
        (let [s (load (modern "{:lights [{:kind :point :pos (fn [t] [t 0 3])}]}"))]
          (assert.is_true (scene.animate s 2))
          (assert.are.same [2 0 3] (. s.lighting.lights 1 :pos)))))))

(describe "lighting: the plan and the shader hold only the features used"
  (fn []
    (it "classic scenes have no modern code"
      (fn []
        (let [text (assert (codegen.shader (assert (plan.scene->plan (assert (scene.load-file "scenes/gallery.fnl")))) :core))]
          (each [_ name (ipairs ["vec3 sky(" "directLight(" "occlusion(" "fogTransmittance(" "visibility("
                                 "kLightCount" "gMaterial" "shininess"])]
            (assert.is_nil (text:find name 1 true) name)))))

    (it "each feature appears only when switched on"
      (fn []
        (let [bare (shader-of (modern "{:ao 0 :specular false :lights [{:kind :sun :softness 0}]}"))
              features {"float occlusion(" "{:ao 0.5}"
                        "float fogTransmittance(" "{:fog 0.01 :ao 0}"
                        "shininess" "{:specular true :ao 0}"
                        "kShadowSteps" "{:ao 0 :lights [{:kind :sun :softness 0.1}]}"}]
          (assert.is_truthy (bare:find "vec3 sky(" 1 true))
          (assert.is_truthy (bare:find "float visibility(" 1 true))
          (each [name lighting (pairs features)]
            (assert.is_nil (bare:find name 1 true) name)
            (assert.is_truthy (: (shader-of (modern lighting)) :find name 1 true) name)))))

    (it "soft shadows need shadows; the key names the features"
      (fn []
        (let [p (assert (plan.scene->plan (load (modern "{:lights [{:kind :sun :softness 0.1}]}" "{:shadows false}"))))]
          (assert.is_false p.lighting.soft?)
          (assert.is_nil (: (codegen.shader p :core) :find "float visibility(" 1 true)))
        (let [p (assert (plan.scene->plan (load (modern "{:fog 0.1 :lights [{:kind :sun} {:kind :point}]}"))))]
          ;; The point light's softness is 0 by default: its hard march is kept.
          (assert.truthy (p.key:find "lighting={features={1=fog 2=occlusion 3=specular} hard?=true lights=2" 1 true) p.key)
          (assert.truthy (p.key:find "soft?=true}" 1 true) p.key))))

    (it "soft shadows hold the hard march only when a light may have softness 0"
      (fn []
        (let [hard-march "if (softness <= 0.0)"
              soft (assert (plan.scene->plan (load (modern "{:lights [{:kind :sun :softness 0.1}]}"))))
              mixed (assert (plan.scene->plan (load (modern "{:lights [{:kind :sun :softness 0.1} {:kind :point :softness 0}]}"))))
              ;; A softness that is a function of time, 0 at t = 0: both marches.
              animated (assert (plan.scene->plan (load (modern "{:lights [{:kind :sun :softness (fn [t] (* 0.01 t))}]}"))))]
          (assert.is_nil (: (codegen.shader soft :core) :find hard-march 1 true))
          (assert.is_truthy (: (codegen.shader mixed :core) :find hard-march 1 true))
          (assert.is_true animated.lighting.soft?)
          (assert.is_truthy (: (codegen.shader animated :core) :find hard-march 1 true))
          (assert.are_not.equal soft.key mixed.key))))

    (it "values are uniforms: moving a light or changing the fog density keeps the key"
      (fn []
        (let [a (plan.scene->plan (load (modern "{:fog 0.1 :lights [{:kind :point :pos [1 2 3]}]}")))
              b (plan.scene->plan (load (modern "{:fog 0.3 :lights [{:kind :point :pos [4 5 6] :intensity 9}]}")))]
          (assert.are.equal a.key b.key))))

    (it "the :model :classic option of the plan (the player's m key) draws the classic model"
      (fn []
        (let [s (load (modern "{}"))
              p (assert (plan.scene->plan s {:model :classic}))]
          (assert.is_nil p.lighting)
          (assert.is_truthy (: (codegen.shader p :core) :find "float lightness(" 1 true)))))))

(describe "lighting: the CPU reference"
  (fn []
    (let [trace (fn [source dir]
                  (let [s (load source)
                        p (assert (plan.scene->plan s))
                        cam (camera.from-scene s)
                        T (reference.tracer s p {:cam-pos cam.pos})
                        [ox oy oz] cam.pos
                        [dx dy dz] dir]
                    (T.trace ox oy oz dx dy dz)))]
      (it "shows the sky, tone-mapped, where a ray meets nothing"
        (fn []
          (let [r (trace "{:lighting {:sky-zenith [0.5 0.5 0.5] :lights [] :exposure 1} :objects []}" [0 0 1])
                expected (math.pow (- 1 (math.exp (- (math.pow 0.5 2.2)))) (/ 1 2.2))]
            (assert.is_false r.hit?)
            (assert.is_true (< (math.abs (- (. r.color 1) expected)) 1e-9)))))

      (it "darkens a corner with ambient occlusion"
        (fn []
          (let [src (fn [ao] (.. "{:camera {:pos [0 0 5] :pitch -90}"
                                 " :lighting {:ao " ao " :ao-radius 1 :lights [] :specular false}"
                                 " :objects [{:kind :plane :height 0} {:kind :box :size [2 2 2] :pos [1.05 0 1]}]}"))
                open (trace (src 0) [0 0 -1])
                occluded (trace (src 1) [0 0 -1])]
            (assert.is_true (< (. occluded.color 1) (- (. open.color 1) 0.02))))))

      (it "gives a soft shadow a penumbra between lit and dark"
        (fn []
          ;; A sun straight above a box: the ground just outside the box's edge is
          ;; in the penumbra of a soft light and lit by a hard one.
          (let [src (fn [softness] (.. "{:camera {:pos [1.1 0 5] :pitch -90}"
                                       " :lighting {:ao 0 :ambient 0 :specular false"
                                       " :lights [{:kind :sun :direction [0.02 0 1] :softness " softness "}]}"
                                       " :objects [{:kind :plane :height 0} {:kind :box :size [2 2 0.5] :pos [0 0 2]}]}"))
                hard (. (trace (src 0) [0 0 -1]) :color 1)
                soft (. (trace (src 0.2) [0 0 -1]) :color 1)]
            (assert.is_true (> hard 0.5))
            (assert.is_true (and (> soft 0.02) (< soft (- hard 0.05))))))))))

;; Through OSMesa: each feature's GLSL against the reference, on scenes/lighting.fnl
;; at the GPU-vs-CPU size. With the feature's lines cut from the GLSL (the reference
;; unchanged), the comparison must fail.
(local mutations
  [["ambient occlusion" "occ *= occlusion(p, n);" ""]
   ["fog" "through *= fogThrough;" ""]
   ["specular" "return radiance * mix(vec3(1.0), albedo, mirror)" "return 0.0 * mix(vec3(1.0), albedo, mirror)"]
   ["soft shadows" "seen = min(seen, closest / (softness * along));" ""]
   ["Fresnel reflection" "radiance += weight * sky(dir);" "radiance += weight * uSkyHorizon;"]
   ["emission" "+ albedo * gMaterial.y;" ";"]
   ["point light falloff" "falloff = 1.0 / (1.0 + r * r);" ""]])

(fn assert-mutant-fails [ctx prepared budget name from to]
  ;; The GLSL of `prepared` with its text `from` replaced by `to` (each a plain
  ;; string) must change and then break `budget` against the reference.
  (var replaced 0)
  (let [st (compare-image prepared
                          (gpu-render ctx prepared
                                      {:source (fn [text]
                                                 (let [(out n) (text:gsub (pick-values 1 (from:gsub "%p" "%%%0"))
                                                                          (pick-values 1 (to:gsub "%%" "%%%%")))]
                                                   (set replaced n)
                                                   out))}))]
    (print (report-line (.. "without " name) st))
    (assert.is_true (> replaced 0) (.. "the mutation of " name " found nothing to change"))
    (assert.is_false (passes? st budget)
                     (.. name " cut from the GLSL still passes: " (report-line name st)))))

(describe "lighting: GPU against the reference"
  (fn []
    (let [(ctx why) (headless.context)]
      (if (not ctx)
          (pending (.. "OSMesa is not available: " (tostring why)))
          (let [prepared (prepare "scenes/lighting.fnl")
                ;; Measured: see the budgets of scenes/lighting.fnl in gpu_vs_cpu_spec.
                budget {:over 2 :max 40}]
            (it "matches with every feature on"
              (fn []
                (let [st (compare-image prepared (gpu-render ctx prepared))]
                  (print (report-line "lighting" st))
                  (assert.is_true (passes? st budget) (describe-failures "lighting" st budget)))))
            (each [_ [name from to] (ipairs mutations)]
              (it (.. "fails when the GLSL loses its " name)
                (fn [] (assert-mutant-fails ctx prepared budget name from to))))))))

(describe "lighting: ambient occlusion's samples in the soft shadow march (issue 42)"
  (fn []
    (it "are the first light's first turns when every light's shadow is soft"
      (fn []
        (let [soft (assert (plan.scene->plan (load (modern "{:lights [{:kind :sun :softness 0.1}]}"))))
              text (codegen.shader soft :core)]
          (assert.are.equal :occlusion soft.lighting.taps)
          ;; One copy of the scene for both: the view no longer calls occlusion().
          (assert.is_nil (text:find "occ *= occlusion(p, n);" 1 true))
          (assert.is_truthy (text:find "float h = mapSome(q, tap);" 1 true))
          (assert.is_truthy (text:find "for (int i = gZero - taps; i < kShadowSteps; i++) {" 1 true))
          (assert.is_truthy (text:find "i == 0 ? kOcclusionTaps : 0, p, n, occ);" 1 true)))))

    (it "are taken by occlusion() where a hard shadow, no shadow or no occlusion is"
      (fn []
        (each [_ source (ipairs [(modern "{:lights [{:kind :sun :softness 0.1} {:kind :point :softness 0}]}")
                                 (modern "{:lights [{:kind :sun :softness 0.1}]}" "{:shadows false}")
                                 (modern "{:lights [{:kind :sun :softness 0}]}")])]
          (let [p (assert (plan.scene->plan (load source)))
                text (codegen.shader p :core)]
            (assert.is_nil p.lighting.taps source)
            (assert.is_truthy (text:find "occ *= occlusion(p, n);" 1 true) source)
            (assert.is_nil (text:find "mapSome" 1 true) source)))
        (let [p (assert (plan.scene->plan (load (modern "{:ao 0 :lights [{:kind :sun :softness 0.1}]}"))))]
          (assert.is_nil p.lighting.taps)
          (assert.is_nil (: (codegen.shader p :core) :find "float occlusion(" 1 true)))))

    (let [(ctx why) (headless.context)]
      (if (not ctx)
          (pending (.. "OSMesa is not available: " (tostring why)))
          ;; The tower (soft shadows only, and occlusion; its budget in
          ;; test/support/budgets.fnl), and a ball and a box on the ground whose
          ;; occlusion comes from the ground (test/fixtures/occlusion-ground.fnl).
          (let [tower (prepare "scenes/twisted-tower.fnl")
                ground (prepare "test/fixtures/occlusion-ground.fnl")
                budget {:over 2 :max 100}]
            (each [_ [name prepared] (ipairs [["the tower" tower] ["the ground's" ground]])]
              (it (.. "match the reference (" name ")")
                (fn []
                  (assert.are.equal :occlusion prepared.plan.lighting.taps)
                  (let [st (compare-image prepared (gpu-render ctx prepared))]
                    (print (report-line (.. name ", occlusion in the shadow march") st))
                    (assert.is_true (passes? st budget) (describe-failures name st budget))))))
            (each [_ [name from to] (ipairs [["the samples' share" "occ *= occlusionOf(taken);" ""]
                                             ["the samples' half-spaces" "float h = mapSome(q, tap);"
                                              "float h = mapSome(q, false);"]])]
              (it (.. "fail the reference without " name)
                (fn [] (assert-mutant-fails ctx ground budget name from to))))))))))

(describe "lighting: a feature declared once (src/render/features/)"
  (fn []
    (it "is found by listing the folder, and its settings are the :lighting section's"
      (fn []
        (let [features (require :src.render.features)
              files (require :src.util.files)]
          ;; One feature per file of the folder, named as its file (a new feature is
          ;; one file and its chunk: nothing here names them).
          (assert.are.same (icollect [_ name (ipairs (assert (files.list-project "src/render/features")))]
                             (name:match "^(.-)%.fnl$"))
                           (icollect [_ d (ipairs features.all)] d.name))
          (assert.is_true (>= (length features.all) 4))
          (let [s (load (modern "{:rim 0.7 :rim-power 2}"))
                p (assert (plan.scene->plan s))]
            (assert.are.equal 0.7 s.lighting.rim)
            (assert.are.same [:occlusion :rim :specular] p.lighting.features)
            (assert.truthy (p.key:find "features={1=occlusion 2=rim 3=specular}" 1 true))
            (assert.truthy (: (codegen.shader p :core) :find "surface += rimLight(cosView, albedo, skyLight);" 1 true)))
          ;; Off by default: neither its code nor its uniform.
          (let [p (assert (plan.scene->plan (load (modern "{}"))))]
            (assert.are.same [:occlusion :specular] p.lighting.features)
            (assert.is_nil (: (codegen.shader p :core) :find "rimLight" 1 true)))
          (assert.truthy (: (load-error (modern "{:rim 2}")) :find "rim" 1 true)))))

    (let [(ctx why) (headless.context)]
      (if (not ctx)
          (pending (.. "OSMesa is not available: " (tostring why)))
          (it "matches the reference with a rim light, and fails without it in the GLSL"
            (fn []
              (with-open [f (assert (io.open "test/out/rim.fnl" :wb))]
                (f:write "{:camera {:pos [0 -6 2] :yaw 90 :pitch -10 :fov 60}
                           :lighting {:rim 0.9 :rim-power 2 :lights [{:kind :sun :softness 0}]}
                           :render {:reflections 1}
                           :objects [{:kind :plane :height 0 :color [0.5 0.5 0.5]}
                                     {:kind :sphere :radius 1 :pos [0 0 1] :color [0.9 0.4 0.2]}
                                     {:kind :box :size [1 1 1] :pos [1.8 0.5 0.5] :color [0.2 0.5 0.9]}]}"))
              (let [prepared (prepare "test/out/rim.fnl")
                    budget {:over 2 :max 40}
                    st (compare-image prepared (gpu-render ctx prepared))
                    (cut n) (: (codegen.shader prepared.plan :core) :gsub
                               "surface %+= rimLight%(cosView, albedo, skyLight%);" "")
                    without (compare-image prepared (gpu-render ctx prepared {:source #cut}))]
                (print (report-line "rim light" st))
                (assert.is_true (passes? st budget) (describe-failures "rim light" st budget))
                (assert.are.equal 1 n)
                (assert.is_false (passes? without budget) (report-line "rim light cut" without)))))))))

(describe "anti-aliasing: supersampling"
  (fn []
    (it "is compiled in only when :samples is above 1, and checked from 1 to 4"
      (fn []
        (assert.is_nil (: (shader-of (.. "{" objects "}")) :find "kSamples" 1 true))
        (let [text (shader-of (.. "{:render {:samples 3} " objects "}"))]
          (assert.is_truthy (text:find "const int kSamples = 3;" 1 true))
          (assert.is_truthy (text:find "vec3 renderSample(vec2 pixel) {" 1 true)))
        (assert.matches "render.samples: must be an integer from 1 to 4, got 5"
                        (load-error (.. "{:render {:samples 5} " objects "}")))))

    (let [(ctx why) (headless.context)]
      (if (not ctx)
          (pending (.. "OSMesa is not available: " (tostring why)))
          (let [prepared (prepare "scenes/lighting.fnl" {:render {:samples 2}})
                budget {:over 2 :max 40}]
            (it "averages the same rays on the GPU and the reference (2 x 2, the modern model)"
              (fn []
                (let [st (compare-image prepared (gpu-render ctx prepared))]
                  (print (report-line "lighting 2x2" st))
                  (assert.is_true (passes? st budget) (describe-failures "lighting 2x2" st budget)))))
            (it "fails when the GLSL takes one sample"
              (fn []
                (let [st (compare-image prepared
                                        (gpu-render ctx prepared
                                                    {:source #(pick-values 1 ($:gsub "return sum / float%(kSamples %* kSamples%);"
                                                                                     "return clamp(renderSample(pixel), 0.0, 1.0);"))}))]
                  (assert.is_false (passes? st budget) (report-line "one sample" st))))))))))

(describe "anti-aliasing: adaptive"
  (fn []
    (it "is compiled in only with :adaptive and :samples above 1"
      (fn []
        (assert.is_nil (: (shader-of (.. "{:render {:adaptive true} " objects "}")) :find "needsSamples" 1 true))
        (let [text (shader-of (.. "{:render {:samples 2 :adaptive true} " objects "}"))]
          (assert.truthy (text:find "const float kContrast = 0.100000;" 1 true)))
        ;; The centre ray's test on its hit's normal, the view's surfaceAt's: no call
        ;; of its own (GLSL inlines each call). The modern view marches and shades
        ;; the primary ray as turn 0 of its bounce loop: one call of each; the
        ;; classic before its loop of bounces.
        (each [_ [source test calls-of-each]
               (ipairs [[(.. "{:render {:samples 2 :adaptive true} " objects "}")
                         "gNeedsSamples = needsSamples(rd, t, n);" 2]
                        [(.. "{:render {:samples 2 :adaptive true :reflections 0} " objects "}")
                         "gNeedsSamples = needsSamples(rd, t, n);" 1]
                        [(modern "{}" "{:samples 2 :adaptive true}")
                         "gNeedsSamples = needsSamples(dir, t, n);" 1]])]
          (let [text (shader-of source)
                ;; Its name followed by "(", less its definition.
                calls (fn [name] (- (select 2 (text:gsub (.. "[^%w_]" name "%(") "")) 1))]
            (assert.is_truthy (text:find test 1 true) source)
            (assert.are.equal calls-of-each (calls "surfaceAt") source)
            (assert.are.equal calls-of-each (calls "raymarch") source)))
        (assert.is_nil (: (shader-of (.. "{:render {:samples 2} " objects "}")) :find "needsSamples" 1 true))))

    (let [(ctx why) (headless.context)]
      (if (not ctx)
          (pending (.. "OSMesa is not available: " (tostring why)))
          (let [prepared (prepare "scenes/gallery.fnl" {:render {:samples 2 :adaptive true}})
                ;; As full supersampling's; an edge test that flips between float and
                ;; double on a pixel changes it by up to the edge's contrast, which the
                ;; over-count allows twice.
                budget {:over 2 :max 40}]
            (it "finds the same edges on the GPU and in the reference (the gallery, 2 x 2)"
              (fn []
                (let [st (compare-image prepared (gpu-render ctx prepared))
                      edges (accumulate [n 0 _ r (ipairs prepared.expected)] (if r.edge? (+ n 1) n))]
                  (print (.. (report-line "gallery adaptive" st) "  edge pixels " edges))
                  (assert.is_true (> edges 0) "no sampled pixel is an edge")
                  (assert.is_true (passes? st budget) (describe-failures "gallery adaptive" st budget)))))
            (it "fails when the GLSL finds no edge"
              (fn []
                ;; Neither the centre ray's tests nor the second ray's contrast.
                (let [blind #(let [text ($:gsub "if %(!gNeedsSamples%) {" "if (true) {")]
                               (pick-values 1 (text:gsub "<= kContrast" "<= 2.0")))
                      st (compare-image prepared (gpu-render ctx prepared {:source blind}))]
                  (assert.is_false (passes? st budget) (report-line "no edges" st))))))))))

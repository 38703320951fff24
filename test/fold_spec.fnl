;; Folded values (issue 25): with the plan option :fold? the scene trees' values are
;; written into the code as constants (what --render, --export-shader and --record of
;; a still scene draw with), so the compiler folds what they make trivial (a stretch
;; by 1, a blend of two equal materials, the stairs' loop). The picture must not
;; change, positions relative to the camera stay uniforms, and the key carries the
;; values (another value is another shader).

(local headless (require :src.backend.headless))
(local load (require :src.scene.load))
(local plan-mod (require :src.render.plan))
(local codegen (require :src.render.codegen))
(local uniforms (require :src.render.uniforms))
(local camera (require :src.render.camera))
(local images (require :test.support.images))

(local width 96)
(local height 64)

(fn render [ctx source us]
  (images.render ctx source us width height))

(fn plan-of [text ?options]
  (let [(s err) (load.load-string text "fold.fnl")]
    (assert s err)
    (values (assert (plan-mod.scene->plan s ?options)) s)))

(describe "folded values"
  (fn []
    (it "writes tree values as float constants, keeps the placement a uniform, and keys the values"
      (fn []
        (let [text "{:objects [{:kind :stretch :factors [1 1 2] :pos [3 4 5] :color [1 0 0]
                                :children [{:kind :octahedron :size 1.5}]}]}"
              (folded) (plan-of text {:fold? true})
              (plain) (plan-of text)
              source (codegen.shader folded :core)]
          ;; The octahedron's size and the stretch's factors are constants...
          (assert.truthy (source:find "sdOctahedron%(p%d+, 1%.5%)") source)
          (assert.truthy (source:find "vec3(1.0, 1.0, 2.0)" 1 true))
          ;; ... the placement (made camera-relative on upload) is read from uTape.
          (assert.truthy (source:find "opTranslate(p, uTape[0].xyz)" 1 true))
          ;; No other row is read, nor copied once per pixel (load-once).
          (assert.falsy (source:find "uTape%[[1-9]%d*%]%."))
          (assert.falsy (source:find "uTape%[[1-9]%d*%] %+"))
          (assert.are_not.equal folded.key plain.key)
          ;; Another value: another folded key, the same unfolded one.
          (let [text2 (text:gsub ":size 1.5" ":size 1.25")]
            (assert.are_not.equal folded.key (. (plan-of text2 {:fold? true}) :key))
            (assert.are.equal plain.key (. (plan-of text2) :key))
            ;; Moving the object keeps the folded key: its position is a uniform.
            (assert.are.equal folded.key
                              (. (plan-of (text:gsub ":pos %[3 4 5%]" ":pos [7 8 9]") {:fold? true})
                                 :key))))))

    (it "writes the settings and lighting values as constants, keeps the view's values uniforms"
      (fn []
        (let [text "{:objects [{:kind :sphere :radius 1 :pos [0 1 0] :color [1 0 0]}]
                     :render {:max-steps 321 :reflections 1}
                     :lighting {:lights [{:kind :sun :direction [1 2 3]}
                                         {:kind :point :pos [4 5 6] :range 10}]
                                :exposure 1.25}}"
              (folded scene) (plan-of text {:fold? true})
              (plain) (plan-of text)
              source (codegen.shader folded :love)
              plain-source (codegen.shader plain :love)]
          ;; The settings are constants, and not copied once per pixel (load-once).
          (assert.truthy (source:find "const int uMaxSteps = 321;" 1 true) source)
          (assert.truthy (source:find "const float uExposure = 1.25;" 1 true))
          (assert.falsy (source:find "gMaxSteps = " 1 true))
          (assert.truthy (plain-source:find "uniform int uMaxSteps;" 1 true))
          (assert.truthy (plain-source:find "gMaxSteps = " 1 true))
          ;; A point light's position follows the camera: the lights stay uniforms, as
          ;; the camera's values and the resolution do.
          (assert.truthy (source:find "uniform vec4 uLights[2];" 1 true))
          (each [_ name (ipairs ["uCamForward" "uProjDist" "uResolution"])]
            (assert.truthy (source:find (.. "uniform [%w]+ " name ";")) name))
          ;; What the constants are: uniforms.fixed, the uniforms no view changes.
          (let [fixed (collect [_ u (ipairs (uniforms.fixed scene folded))] u.name true)
                far (doto (camera.from-scene scene) (tset :pos [100 -50 7]))]
            (assert.truthy fixed.uMaxSteps)
            (assert.falsy fixed.uLights)
            ;; Every uniform that fixed leaves out changes with the view or is a texture.
            (each [_ u (ipairs (uniforms.pack scene folded far 320 180))]
              (when (and u.values (not (. fixed u.name)))
                (assert.truthy u.view? u.name))))
          ;; Another setting: another folded key, the same unfolded one.
          (let [text2 (text:gsub ":max%-steps 321" ":max-steps 322")]
            (assert.are_not.equal folded.key (. (plan-of text2 {:fold? true}) :key))
            (assert.are.equal plain.key (. (plan-of text2) :key))))))

    (local ctx (assert (headless.context)))
    (each [_ file (ipairs ["scenes/organic.fnl" "scenes/twisted-tower.fnl" "scenes/flower.fnl"
                           "scenes/colonnade.fnl" "scenes/machined-part.fnl" "scenes/custom.fnl"])]
      (it (.. file ": draws the same picture folded")
        (fn []
          (let [scene (assert (load.load-file file))
                plain (assert (plan-mod.scene->plan scene))
                folded (assert (plan-mod.scene->plan scene {:fold? true}))
                cam (camera.from-scene scene)
                a (render ctx (codegen.shader plain :core) (uniforms.pack scene plain cam width height))
                b (render ctx (codegen.shader folded :core) (uniforms.pack scene folded cam width height))
                (worst over) (images.channel-difference a b width height)]
            (print (string.format "\nfold %s: largest channel difference %d, %d of %d pixels over 2/255"
                                  file worst over (* width height)))
            ;; The tolerance of test/export_spec.fnl, for the same reason: the constants
            ;; are the uniforms' float32 values, but the compiler folds constant
            ;; expressions in other orders, with other rounding.
            (assert.is_true (<= over (* 0.01 width height)) (.. over " pixels over 2/255"))
            (assert.is_true (<= worst 32) (.. "largest channel difference " worst))))))))

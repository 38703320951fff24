;; Every shader the generator can emit passes glslangValidator and compiles and links
;; on the real driver (Mesa llvmpipe through OSMesa), and the uniform budget holds at
;; its limit.
(local scene-mod (require :src.scene.load))
(local plan-mod (require :src.render.plan))
(local codegen (require :src.render.codegen))
(local headless (require :src.backend.headless))

(local glslang-ok? (. (require :test.support.glslang) :ok?))

(fn synthetic-scene [kinds {: shadows : reflections : glow}]
  (let [objects (icollect [_ k (ipairs kinds)]
                  (case k
                    :sphere "{:kind :sphere :radius 1 :pos [0 0 1]}"
                    :box "{:kind :box :size [1 2 3] :pos [3 0 1]}"
                    :plane "{:kind :plane :height 0}"))]
    (assert (scene-mod.load-string
             (string.format "{:render {:shadows %s :reflections %d :glow %s} :objects [%s]}"
                            (tostring shadows) reflections (tostring glow)
                            (table.concat objects " "))
             "synthetic.fnl"))))

(fn kind-subsets []
  (let [all [:sphere :box :plane]
        out []]
    (for [mask 0 7]
      (table.insert out (icollect [i k (ipairs all)]
                          (when (not= 0 (bit.band mask (bit.lshift 1 (- i 1)))) k))))
    out))

(fn plan! [scene ?options]
  (let [(p err) (plan-mod.scene->plan scene ?options)]
    (assert p err)
    p))

(fn all-plans []
  "One plan for every combination of kinds, features and views, plus the uber plans."
  (let [plans []]
    (each [_ kinds (ipairs (kind-subsets))]
      (each [_ shadows (ipairs [false true])]
        (each [_ reflections (ipairs [0 2])]
          (each [_ glow (ipairs [false true])]
            (let [scene (synthetic-scene kinds {: shadows : reflections : glow})]
              (table.insert plans (plan! scene))
              (when (and shadows (= reflections 2) glow)
                (each [_ view (ipairs [:normals :glow :heat])]
                  (table.insert plans (plan! scene {: view})))
                (each [_ view (ipairs plan-mod.views)]
                  (table.insert plans (plan! scene {: view :uber? true})))))))))
    plans))

(fn many-spheres [n]
  (let [objects (fcollect [i 1 n]
                  (string.format "{:kind :sphere :radius 0.1 :pos [%d 0 0]}" i))]
    (.. "{:objects [" (table.concat objects "\n") "]}")))

(describe "generated shaders"
  (fn []
    (local plans (all-plans))

    (it "have one shader text per structure key, and a distinct text for each key"
      (fn []
        ;; The shader cache is keyed by structure: equal keys must mean equal text.
        (let [by-key {} by-text {}]
          (each [_ p (ipairs plans)]
            (let [text (codegen.shader p :core)]
              (when (. by-key p.key) (assert.are.equal (. by-key p.key) text))
              (tset by-key p.key text)
              (tset by-text text p.key)))
          (let [count-keys (accumulate [n 0 _ (pairs by-key)] (+ n 1))]
            ;; 8 kind subsets x 8 feature sets + 3 other views each, and an uber
            ;; shader per subset and view (every feature compiled in, the scene's
            ;; objects on its tape).
            (assert.are.equal (+ (* 8 (+ 8 3)) (* 8 4)) count-keys)
            (assert.are.equal count-keys (accumulate [n 0 _ (pairs by-text)] (+ n 1)))))))

    (it "pass glslangValidator (core target)"
      (fn []
        (each [_ p (ipairs plans)]
          (let [(ok? out) (glslang-ok? (codegen.shader p :core))]
            (assert (= ok? true) (.. p.key ": " out))))))

    (it "compile and link on the real driver"
      (fn []
        (let [(ctx why) (headless.context)]
          (if (not ctx)
              (pending (.. "OSMesa unavailable: " why))
              (each [_ p (ipairs plans)]
                (let [(prog err) (headless.compile ctx (codegen.shader p :core))]
                  (assert (not= nil prog) (.. p.key ": " (tostring err)))
                  (headless.release ctx prog)))))))))

(describe "the uniform budget"
  (fn []
    (local per-sphere 2)
    (local largest (math.floor (/ (- plan-mod.default-uniform-limit plan-mod.fixed-uniform-vectors)
                                  per-sphere)))

    (it "matches the driver's limit"
      (fn []
        (let [(ctx why) (headless.context)]
          (if (not ctx)
              (pending (.. "OSMesa unavailable: " why))
              (assert.are.equal plan-mod.default-uniform-limit
                                (. (headless.limits ctx) :max-fragment-uniform-vectors))))))

    ;; Spheres in uniform arrays (:field? false, :grids? false): from 16 on a scene's
    ;; spheres form a field in textures, and an instance group has a grid and its rows
    ;; in a texture; neither takes per-object uniforms (field_spec, grid_spec).
    (it "fits the largest scene, which compiles, and refuses one more object clearly"
      (fn []
        (let [scene (assert (scene-mod.load-string (many-spheres largest) "big.fnl"))
              p (assert (plan-mod.scene->plan scene {:field? false :grids? false}))
              (ctx why) (headless.context)]
          (assert.are.equal plan-mod.default-uniform-limit p.uniform-vectors)
          (when ctx
            (let [(prog err) (headless.compile ctx (codegen.shader p :core))]
              (assert (not= nil prog) (tostring err))
              (headless.release ctx prog)))
          (let [bigger (assert (scene-mod.load-string (many-spheres (+ largest 1)) "big.fnl"))
                (none msg) (plan-mod.scene->plan bigger {:field? false :grids? false})]
            (assert.is_nil none)
            (assert.are.equal
             "big.fnl: objects: the scene needs 4098 uniform vectors but the driver allows 4096 (32 are reserved); remove objects worth 2 vectors (a sphere takes 2)"
             msg)))))))

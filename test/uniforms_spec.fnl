;; Specs for src/render/uniforms.fnl: names and order, camera-relative values in double
;; precision, padding in uber plans, feature uniforms and value counts.
(local ffi (require :ffi))
(local scene (require :src.scene.load))
(local plan (require :src.render.plan))
(local camera (require :src.render.camera))
(local uniforms (require :src.render.uniforms))

(fn load [source]
  (assert (scene.load-string source "t.fnl")))

(fn by-name [list]
  (collect [_ u (ipairs list)] u.name u))

(fn near [expected actual ?tol]
  (let [tol (or ?tol 1e-12)]
    (assert (<= (math.abs (- expected actual)) tol)
            (.. "expected " expected " got " actual))))

(fn pack-scene [s ?options ?cam]
  (let [p (assert (plan.scene->plan s ?options))
        cam (or ?cam (camera.from-scene s))]
    (values (uniforms.pack s p cam 640 480) p)))

(local seed (assert (scene.load-file "scenes/seed.fnl")))

(describe "uniforms: names and order"
  (fn []
    (it "lists the seed's uniforms sorted by name"
      (fn []
        (let [list (pack-scene seed)]
          (assert.are.same ["uBoxCenter" "uBoxColor" "uBoxHalfSize" "uCamForward" "uCamRight"
                            "uCamUp" "uDrawDist" "uEnvColor" "uEpsilon" "uLightPos"
                            "uMaxSteps" "uPlaneColor" "uPlaneHeight" "uProjDist"
                            "uReflections" "uResolution" "uSphere" "uSphereColor"]
                           (icollect [_ u (ipairs list)] u.name)))))

    (it "is sorted for any plan"
      (fn []
        (each [_ options (ipairs [{} {:uber? true} {:view :heat} {:reflections 0}])]
          (let [list (pack-scene seed options)]
            (for [i 2 (length list)]
              (assert.is_true (< (. list (- i 1) :name) (. list i :name))))))))

    (it "gives every uniform the type the shader declares"
      (fn []
        (let [u (by-name (pack-scene seed {:uber? true}))]
          (each [name t (pairs {:uResolution :vec2 :uCamForward :vec3 :uCamRight :vec3
                                :uCamUp :vec3 :uProjDist :float :uLightPos :vec3
                                :uEnvColor :vec3 :uMaxSteps :int :uEpsilon :float
                                :uDrawDist :float :uReflections :int :uShadows :bool
                                :uGlow :bool :uCountSphere :int :uCountBox :int
                                :uCountPlane :int :uSphere :vec4 :uSphereColor :vec3
                                :uBoxCenter :vec3 :uBoxHalfSize :vec3 :uBoxColor :vec3
                                :uPlaneHeight :float :uPlaneColor :vec3})]
            (assert.are.equal t (. u name :type) name)))))))

(describe "uniforms: values"
  (fn []
    (it "packs the seed's common uniforms"
      (fn []
        (let [u (by-name (pack-scene seed))
              (f r up) (camera.basis (camera.from-scene seed))]
          (assert.are.same [640 480] u.uResolution.values)
          (assert.are.same f u.uCamForward.values)
          (assert.are.same r u.uCamRight.values)
          (assert.are.same up u.uCamUp.values)
          (near (math.sqrt 3) (. u.uProjDist.values 1) 1e-12)
          (assert.are.same [-50 -30 0] u.uLightPos.values)
          (assert.are.same [0.901 0.976 1] u.uEnvColor.values)
          (assert.are.same [500] u.uMaxSteps.values)
          (assert.are.same [1e-4] u.uEpsilon.values)
          (assert.are.same [1000] u.uDrawDist.values)
          (assert.are.same [3] u.uReflections.values))))

    (it "packs the seed's objects camera-relative, in plan order"
      (fn []
        (let [u (by-name (pack-scene seed))]
          ;; Camera at [20 50 20].
          (assert.are.same [(- -2.7 20) (- 2.5 50) (- 2.5 20) 2.5
                            (- 6 20) (- -20 50) (- 10 20) 10]
                           u.uSphere.values)
          (assert.are.equal 2 u.uSphere.count)
          (assert.are.same [0.56 0.11 0.05 0.97 0.71 0.17] u.uSphereColor.values)
          (assert.are.same [(- -2.7 20) -52 -17.5 (- 2.7 20) -48 -17.5 -20 -50 -12.5]
                           u.uBoxCenter.values)
          (assert.are.same [2.5 2.5 2.5 2.5 2.5 2.5 2.5 2.5 2.5] u.uBoxHalfSize.values)
          (assert.are.same [0.79 0.69 0.59 0.75 0.08 0.66 0.33 0.73 0.42] u.uBoxColor.values)
          (assert.are.same [-20] u.uPlaneHeight.values)
          (assert.are.same [0.97 0.27 0.35] u.uPlaneColor.values))))

    (it "makes positions camera-relative in double precision"
      (fn []
        (let [s (load "{:objects [{:kind :sphere :pos [100001 0 0] :radius 0.5}
                                  {:kind :box :pos [100000.1 0 0]}
                                  {:kind :plane :height 1}]
                        :light {:pos [100002 3 4]}}")
              cam {:pos [1e5 0 0] :yaw 0 :pitch 0 :fov 60}
              u (by-name (pack-scene s nil cam))]
          (assert.are.same [1 0 0 0.5] u.uSphere.values)
          (assert.are.same [2 3 4] u.uLightPos.values)
          (assert.are.same [1] u.uPlaneHeight.values)
          ;; 100000.1 - 1e5 in double is within 1e-11 of 0.1; in float32 it would be
          ;; 0.1015625 (the nearest float32 to 100000.1 is 100000.1015625).
          (let [x (. u.uBoxCenter.values 1)
                f32 (ffi.new "float[2]" 100000.1 100000)]
            (near 0.1 x 1e-10)
            (assert.are.equal 0.1015625 (- (. f32 0) (. f32 1)))))))

    (it "follows the camera it is given, not the scene's"
      (fn []
        (let [cam (camera.from-scene seed)]
          (camera.elevate! cam 5)
          (let [u (by-name (uniforms.pack seed (assert (plan.scene->plan seed)) cam 10 10))]
            (assert.are.same [-25] u.uPlaneHeight.values)
            (assert.are.same [-50 -30 -5] u.uLightPos.values)
            (assert.are.same [10 10] u.uResolution.values)))))))

(describe "uniforms: features and padding"
  (fn []
    (it "sends uReflections only when reflections are on"
      (fn []
        (assert.is_nil (. (by-name (pack-scene seed {:reflections 0})) :uReflections))
        (assert.is_nil (. (by-name (pack-scene seed {:view :normals})) :uReflections))
        (assert.is_nil (. (by-name (pack-scene (load "{:objects [] :render {:reflections 0}}")))
                          :uReflections))
        (assert.are.same [7] (. (by-name (pack-scene seed {:reflections 7})) :uReflections :values))))

    (it "sends switches and counts only to the uber shader"
      (fn []
        (let [u (by-name (pack-scene seed))]
          (assert.is_nil u.uShadows)
          (assert.is_nil u.uGlow)
          (assert.is_nil u.uCountSphere))
        (let [u (by-name (pack-scene seed {:uber? true}))]
          (assert.are.same [1] u.uShadows.values)
          (assert.are.same [0] u.uGlow.values)
          (assert.are.same [2] u.uCountSphere.values)
          (assert.are.same [3] u.uCountBox.values)
          (assert.are.same [1] u.uCountPlane.values)
          (assert.are.same [3] u.uReflections.values))
        (let [u (by-name (pack-scene (load "{:objects [] :render {:shadows false :glow true
                                                                  :reflections 0}}")
                                     {:uber? true}))]
          (assert.are.same [0] u.uShadows.values)
          (assert.are.same [1] u.uGlow.values)
          (assert.are.same [0] u.uReflections.values))))

    (it "pads the uber shader's empty kinds with zeros"
      (fn []
        (let [u (by-name (pack-scene (load "{:objects [{:kind :sphere :pos [1 2 3] :radius 2}]}")
                                     {:uber? true} {:pos [0 0 0] :yaw 0 :pitch 0 :fov 60}))]
          (assert.are.same [1 2 3 2] u.uSphere.values)
          (assert.are.same [0] u.uCountBox.values)
          (assert.are.same [0 0 0] u.uBoxCenter.values)
          (assert.are.same [0 0 0] u.uBoxHalfSize.values)
          (assert.are.same [0 0 0] u.uBoxColor.values)
          (assert.are.equal 1 u.uBoxCenter.count)
          (assert.are.same [0] u.uCountPlane.values)
          (assert.are.same [0] u.uPlaneHeight.values)
          (assert.are.same [0 0 0] u.uPlaneColor.values))))

    (it "sends capacity times components values for every array"
      (fn []
        (each [_ options (ipairs [{} {:uber? true}])]
          (each [_ source (ipairs ["{:objects []}" "{:objects [{:kind :box} {:kind :box}]}"])]
            (let [(list p) (pack-scene (load source) options)
                  capacity (collect [_ k (ipairs p.kinds)] k.kind k.capacity)
                  arrays (icollect [_ u (ipairs list)] (when (and u.count (not= u.name "uBounds")) u))]
              (each [_ u (ipairs arrays)]
                (let [kind (if (u.name:find "^uSphere") :sphere (u.name:find "^uLargeSphere") :large-sphere
                               (u.name:find "^uBox") :box :plane)]
                  (assert.are.equal (. capacity kind) u.count)
                  (assert.are.equal (* u.count (. uniforms.components u.type))
                                    (length u.values))))
              ;; uber: 2 sphere + 3 large-sphere + 3 box + 2 plane arrays.
              (assert.are.equal (if options.uber? 10 (source:find ":box") 3 0)
                                (length arrays)))))
        (each [_ u (ipairs (pack-scene seed))]
          (let [n (* (or u.count 1) (. uniforms.components u.type))]
            (assert.are.equal n (length u.values) u.name)))))))

;; tier: fast
;; Specs for src/render/uniforms.fnl: names and order, camera-relative values in double
;; precision, feature uniforms and value counts.
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
          (assert.are.same ["uCamForward" "uCamRight" "uCamUp" "uDrawDist" "uEnvColor"
                            "uEpsilon" "uLightPos" "uMaxSteps" "uProjDist" "uReflections"
                            "uResolution" "uTape"]
                           (icollect [_ u (ipairs list)] u.name)))))

    (it "is sorted for any plan"
      (fn []
        (each [_ options (ipairs [{} {:uber? true} {:view :heat} {:reflections 0}])]
          (let [list (pack-scene seed options)]
            (for [i 2 (length list)]
              (assert.is_true (< (. list (- i 1) :name) (. list i :name))))))))

    (it "packs what the hand-written floor of make bench declares, with the tape's rows an array"
      (fn []
        ;; test/bench/seed-analytic.glsl takes the marcher's uniforms; make bench packs
        ;; them with :tape-texture? false (test/bench/report.fnl).
        (let [text (with-open [f (assert (io.open "test/bench/seed-analytic.glsl" :rb))] (f:read :*a))
              u (by-name (pack-scene seed {:tape-texture? false}))
              declared (icollect [ty name count (text:gmatch "\nuniform (%w+) (u%w+)%[?(%d*)%]?;")]
                         [ty name count])]
          (assert.are.equal 12 (length declared))
          (each [_ [ty name count] (ipairs declared)]
            (let [v (. u name)]
              (assert.truthy v name)
              (assert.are.equal ty v.type name)
              (when (not= count "") (assert.are.equal (tonumber count) v.count name)))))))

    (it "gives every uniform the type the shader declares"
      (fn []
        (let [u (by-name (pack-scene seed {:uber? true}))]
          (each [name t (pairs {:uResolution :vec2 :uCamForward :vec3 :uCamRight :vec3
                                :uCamUp :vec3 :uProjDist :float :uLightPos :vec3
                                :uEnvColor :vec3 :uMaxSteps :int :uEpsilon :float
                                :uDrawDist :float :uReflections :int :uShadows :bool
                                :uGlow :bool :uTape :texture})]
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

    (it "packs the seed's objects camera-relative, in the tape's rows"
      (fn []
        (let [u (by-name (pack-scene seed))
              row (fn [i] (fcollect [k 1 4] (. u.uTape.texture.data (+ (* 4 i) k))))]
          ;; A row a texel (emit-glsl.tape-texel): 16 rows and the 10 values of the
          ;; plan's :texels fit one line.
          (assert.are.equal 26 u.uTape.count)
          (assert.are.same [26 1] [u.uTape.texture.width u.uTape.texture.height])
          ;; Camera at [20 50 20]. The first box: its place, half size, material
          ;; (colour, a full mirror).
          (assert.are.same [(- -2.7 20) -52 -17.5 0] (row 0))
          (assert.are.same [2.5 2.5 2.5 0] (row 1))
          (assert.are.same [0.79 0.69 0.59 1] (row 2))
          (assert.are.same [-20 -50 -12.5 0] (row 6))
          ;; A sphere's radius beside its place.
          (assert.are.same [(- -2.7 20) (- 2.5 50) (- 2.5 20) 2.5] (row 9))
          (assert.are.same [0.56 0.11 0.05 1] (row 10))
          (assert.are.same [(- 6 20) (- -20 50) (- 10 20) 10] (row 11))
          ;; The plane reads the shader's point: its height takes the camera off (an
          ;; unused place of zero before it).
          (assert.are.same [0 0 0 0] (row 13))
          (assert.are.same [0 0 1 -20] (row 14))
          (assert.are.same [0.97 0.27 0.35 1] (row 15))
          ;; Then the values a pixel copies once, a texel each in pack's order (the
          ;; plan's :texels): the draw distance, the step budget.
          (let [p (assert (plan.scene->plan seed))
                at (fn [name] (accumulate [n 16 _ t (ipairs p.texels) &until (= t.name name)]
                                (+ n (or t.count 1))))]
            (assert.are.same [1000 0 0 0] (row (at "uDrawDist")))
            (assert.are.same [500 0 0 0] (row (at "uMaxSteps")))
            (assert.are.same [-50 -30 0 0] (row (at "uLightPos")))))))

    (it "lays the values out in texels by name and count only: a value edit keeps the shader"
      (fn []
        ;; The tower with a dimmer sun: the same plan (key, texels), and the image
        ;; differs in the light's colour texel alone.
        (let [bright (assert (scene.load-file "scenes/twisted-tower.fnl"))
              dim (doto (assert (scene.load-file "scenes/twisted-tower.fnl"))
                    (tset :lighting :lights 1 :intensity 0.6))
              (ub pb) (pack-scene bright)
              (ud pd) (pack-scene dim)
              rows (length pb.tape.rows)
              ;; Its texel: after the rows and each element of the values before it.
              texel (accumulate [n rows _ t (ipairs pb.texels) &until (= t.name "uLightColors")]
                      (+ n (or t.count 1)))
              tb (. (by-name ub) :uTape :texture :data)
              td (. (by-name ud) :uTape :texture :data)
              differ (icollect [i x (ipairs tb)] (when (not= x (. td i)) (math.floor (/ (- i 1) 4))))]
          (assert.are.equal pb.key pd.key)
          (assert.are.same pb.texels pd.texels)
          (assert.are.equal (length tb) (length td))
          ;; Three colour components of one texel (its softness is the same).
          (assert.are.same [texel texel texel] differ)
          (near (* 0.2 (. tb (+ (* 4 texel) 1))) (. td (+ (* 4 texel) 1)) 1e-9))))

    (it "makes positions camera-relative in double precision"
      (fn []
        (let [s (load "{:objects [{:kind :sphere :pos [100001 0 0] :radius 0.5}
                                  {:kind :box :pos [100000.1 0 0]}
                                  {:kind :plane :height 1}]
                        :light {:pos [100002 3 4]}}")
              cam {:pos [1e5 0 0] :yaw 0 :pitch 0 :fov 60}
              u (by-name (pack-scene s {:bounds? false} cam))
              row (fn [i] (fcollect [k 1 4] (. u.uTape.texture.data (+ (* 4 i) k))))]
          (assert.are.same [1 0 0 0.5] (row 0))
          (assert.are.same [2 3 4] u.uLightPos.values)
          (assert.are.same [0 0 1 1] (row 6))
          ;; 100000.1 - 1e5 in double is within 1e-11 of 0.1; in float32 it would be
          ;; 0.1015625 (the nearest float32 to 100000.1 is 100000.1015625).
          (let [x (. (row 2) 1)
                f32 (ffi.new "float[2]" 100000.1 100000)]
            (near 0.1 x 1e-10)
            (assert.are.equal 0.1015625 (- (. f32 0) (. f32 1)))))))

    (it "follows the camera it is given, not the scene's"
      (fn []
        (let [cam (camera.from-scene seed)]
          (camera.elevate! cam 5)
          (let [u (by-name (uniforms.pack seed (assert (plan.scene->plan seed)) cam 10 10))]
            ;; The plane's height, camera-relative.
            (assert.are.same -25 (. u.uTape.texture.data (+ (* 4 14) 4)))
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

    (it "sends switches only to the uber shader"
      (fn []
        (let [u (by-name (pack-scene seed))]
          (assert.is_nil u.uShadows)
          (assert.is_nil u.uGlow))
        (let [u (by-name (pack-scene seed {:uber? true}))]
          (assert.are.same [1] u.uShadows.values)
          (assert.are.same [0] u.uGlow.values)
          (assert.are.same [3] u.uReflections.values))
        (let [u (by-name (pack-scene (load "{:objects [] :render {:shadows false :glow true
                                                                  :reflections 0}}")
                                     {:uber? true}))]
          (assert.are.same [0] u.uShadows.values)
          (assert.are.same [1] u.uGlow.values)
          (assert.are.same [0] u.uReflections.values))))

    (it "sends an instance group's rows in uInstances, each member's camera-relative"
      (fn []
        (let [s (load (.. "{:objects [" (string.rep "{:kind :sphere :pos [1 2 3] :radius 2} " 9) "]}"))
              u (by-name (pack-scene s {:bounds? false} {:pos [0 0 1] :yaw 0 :pitch 0 :fov 60}))]
          (assert.is_nil u.uTape)
          (assert.are.equal 18 u.uInstances.count)
          (for [m 0 8]
            (assert.are.same [1 2 2 2 1 1 1 1]
                             (fcollect [k 1 8] (. u.uInstances.values (+ (* 8 m) k))))))))

    (it "sends count times components values for every array"
      (fn []
        (each [_ source (ipairs ["{:objects []}" "{:objects [{:kind :box} {:kind :box}]}"
                                 (.. "{:objects [" (string.rep "{:kind :box} " 9) "]}")])]
          (let [list (pack-scene (load source))
                arrays (icollect [_ u (ipairs list)] (when (and u.count (not= u.name "uBounds")) u))]
            (each [_ u (ipairs arrays)]
              (if (= u.type :texture)
                  (assert.are.equal (* u.count 4) (length u.texture.data))
                  (assert.are.equal (* u.count (. uniforms.components u.type)) (length u.values))))
            (assert.are.equal (if (source:find ":box") 1 0) (length arrays))))
        (each [_ u (ipairs (pack-scene seed))]
          (if (= u.type :texture)
              (assert.are.equal (* u.count 4) (length u.texture.data) u.name)
              (let [n (* (or u.count 1) (. uniforms.components u.type))]
                (assert.are.equal n (length u.values) u.name))))))))

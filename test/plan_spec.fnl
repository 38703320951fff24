;; tier: fast
;; Specs for src/render/plan.fnl: kinds and counts, features, views, the structure key and the
;; uniform budget.
(local scene (require :src.scene.load))
(local plan (require :src.render.plan))

(fn load [source]
  (assert (scene.load-string source "t.fnl")))

(fn plan-of [source ?options]
  (assert (plan.scene->plan (load source) ?options)))

(fn key-of [source ?options]
  (. (plan-of source ?options) :key))

(fn spheres [n]
  "A scene table with `n` default spheres (built directly: the loader caps objects at 1000)."
  (let [s (load "{:objects []}")]
    (set s.objects (fcollect [i 1 n] {:kind :sphere :index i :pos [i 0 0] :radius 1
                                      :color [1 1 1]}))
    s))

(local seed (assert (scene.load-file "scenes/seed.fnl")))

(describe "plan: objects and the tape"
  (fn []
    (it "lowers every object of the seed into the tape, in file order"
      (fn []
        (let [p (assert (plan.scene->plan seed))]
          (assert.are.same [1 2 3 4 5 6] (icollect [_ o (ipairs p.objects)] o.index))
          (assert.are.same [:box :box :box :sphere :sphere :plane]
                           (icollect [_ o (ipairs p.tape.objects)] (. o.info.children 1 :kind)))
          (assert.are.equal 6 p.tape.count)
          (assert.are.equal :shaded p.view)
          (assert.are.equal false p.uber?)
          (assert.are.equal true p.shadows?)
          (assert.are.equal true p.reflections?)
          (assert.are.equal false p.glow?)
          (assert.are.equal 3 p.reflections)
          ;; 32 reserved, 16 rows: a box takes 3 (its place, its half size, its
          ;; material), a sphere 2 (its radius beside its place), the plane 3 (an
          ;; unused place, its normal and height, its material).
          (assert.are.equal 48 p.uniform-vectors)
          ;; The seed keeps the article's march: no bounds.
          (assert.is_nil p.bounds)
          ;; The key: every field of the plan but the values, the tape by its key.
          (assert.are.equal (.. "adaptive?=false edge-tests={contrast=0.1 edge-turn=0.1 "
                                "grazing=0.3 limb-turn=0.0001 second={1=0.875 2=0.875}} "
                                "exact-normals?=false glow?=false hit-test=fixed load-once?=true "
                                "mirrors?=false normals=one-sided normals-of=scene "
                                "out-of-steps=surface reflections?=true relaxed?=false samples=1 "
                                "shadows?=true tape=translate( box ) ; translate( box ) ; "
                                "translate( box ) ; translate( sphere ) ; translate( sphere ) ; "
                                "translate( ground ) identity ; rows:16 tape-texture?=true uber?=false view=shaded")
                            p.key))))

    (it "draws the article's flat objects as the same leaves as tree nodes"
      (fn []
        ;; A sphere with :mirror is a tree node; without, a flat object: one code.
        (let [flat (plan-of "{:objects [{:kind :sphere :radius 2 :pos [1 2 3] :color [1 0 0]}]}")
              tree (plan-of "{:objects [{:kind :sphere :radius 2 :pos [1 2 3] :color [1 0 0] :mirror 1}]}")]
          (assert.are.equal flat.key tree.key)
          (assert.are.same flat.tape.rows tree.tape.rows))))

    (it "groups nine or more objects of one structure into a loop over their rows"
      (fn []
        (let [p (assert (plan.scene->plan (spheres 12)))
              [o] p.tape.objects]
          (assert.are.equal 1 (length p.tape.objects))
          (assert.are.same {:count 12 :base 0 :stride 2} o.instances)
          (assert.are.equal 12 p.tape.count)
          (assert.are.equal 24 (length p.tape.instances.rows))
          (assert.are.same (fcollect [i 1 12] i) (icollect [_ ob (ipairs p.objects)] ob.index))
          (assert.is_truthy (p.key:find "group:12[translate( sphere ) ;]" 1 true)))
        ;; Eight are written out one by one.
        (let [p (assert (plan.scene->plan (spheres 8)))]
          (assert.are.equal 8 (length p.tape.objects))
          (assert.are.equal 0 (length p.tape.instances.rows)))))

    (it "holds an empty tape for an empty scene"
      (fn []
        (let [p (plan-of "{:objects []}")]
          (assert.are.same [] p.tape.objects)
          (assert.are.same [] p.objects)
          (assert.are.equal 32 p.uniform-vectors)
          (assert.truthy (p.key:find "bounds={count=0}" 1 true))
          (assert.truthy (p.key:find "tape=rows:0" 1 true)))))

    (it "compiles every feature in an uber plan"
      (fn []
        (let [p (plan-of "{:objects [{:kind :sphere} {:kind :sphere}]}" {:uber? true})]
          (assert.are.equal true p.uber?)
          (assert.are.equal true p.shadows?)
          (assert.are.equal true p.reflections?)
          (assert.are.equal true p.glow?)
          (assert.are.equal (+ 32 4) p.uniform-vectors)
          (assert.truthy (p.key:find "uber?=true" 1 true)))))))

(describe "plan: features and views"
  (fn []
    (it "turns features on from the scene"
      (fn []
        (let [p (plan-of "{:objects [] :render {:shadows false :reflections 0 :glow true}}")]
          (assert.are.equal false p.shadows?)
          (assert.are.equal false p.reflections?)
          (assert.are.equal true p.glow?)
          (assert.are.equal 0 p.reflections))))

    (it "lets the :reflections option override the scene"
      (fn []
        (let [p (assert (plan.scene->plan seed {:reflections 0}))]
          (assert.are.equal false p.reflections?)
          (assert.are.equal 0 p.reflections))
        (let [p (plan-of "{:objects [] :render {:reflections 0}}" {:reflections 5})]
          (assert.are.equal true p.reflections?)
          (assert.are.equal 5 p.reflections))))

    (it "has no shading features outside the shaded view"
      (fn []
        (each [_ view (ipairs [:normals :glow :heat])]
          (let [p (assert (plan.scene->plan seed {: view}))]
            (assert.are.equal view p.view)
            (assert.are.equal false p.shadows?)
            (assert.are.equal false p.reflections?)
            (assert.are.equal false p.glow?)
            (assert.truthy (p.key:find (.. "view=" view) 1 true))
            (assert.are.equal (= view :normals) (not= nil (p.key:find "normals=one-sided" 1 true)))))))

    (it "knows its views and rejects others"
      (fn []
        (assert.are.same [:shaded :normals :glow :heat] plan.views)
        (assert.is_true (plan.view? :heat))
        (assert.is_false (plan.view? :bogus))
        (let [(ok err) (pcall plan.scene->plan seed {:view :bogus})]
          (assert.is_false ok)
          (assert.truthy (: (tostring err) :find "unknown view bogus" 1 true)))))))

(describe "plan: structure key"
  (fn []
    (local base "{:objects [{:kind :sphere :pos [1 2 3] :color [1 0 0]}
                            {:kind :box}]
                  :light {:pos [1 1 1]}
                  :render {:epsilon 1e-4 :reflections 2 :shadows true :glow false}}")
    (local base-key (key-of base))

    (it "is the expected text"
      (fn []
        (each [_ part (ipairs ["shadows?=true" "reflections?=true" "relaxed?=true" "hit-test=relative"
                               "normals=tetrahedron" "bounds={count=2}" "view=shaded"
                               "tape=translate( sphere ) ; translate( box ) ; rows:5"])]
          (assert.truthy (base-key:find part 1 true) part))))

    (it "is derived from every field of the plan but its values"
      (fn []
        ;; A field no one listed is in the key.
        (let [p (plan-of base)]
          (set p.future-feature? true)
          (assert.are_not.equal base-key ((. plan :structure-key) p)))
        ;; Values are not: the reflection count, the objects.
        (let [p (plan-of base)]
          (set p.reflections 7)
          (set p.objects [])
          (assert.are.equal base-key ((. plan :structure-key) p)))
        ;; A field's object count is in its code (gObject's ranges).
        (let [many (fn [n] (.. "{:objects [" (string.rep "{:kind :sphere :pos [1 2 3]} " n) "]}"))]
          (assert.are_not.equal (key-of (many 20)) (key-of (many 21))))))

    (it "changes with structure"
      (fn []
        (each [_ [what source options]
               (ipairs
                 [["count" "{:objects [{:kind :sphere} {:kind :sphere} {:kind :box}]
                             :render {:reflections 2}}"]
                  ["kind" "{:objects [{:kind :sphere} {:kind :plane}] :render {:reflections 2}}"]
                  ["missing kind" "{:objects [{:kind :sphere}] :render {:reflections 2}}"]
                  ;; The tape's code follows the file's order.
                  ["order" "{:objects [{:kind :box} {:kind :sphere}] :render {:reflections 2}}"]
                  ["shadows" "{:objects [{:kind :sphere} {:kind :box}]
                               :render {:reflections 2 :shadows false}}"]
                  ["reflections" "{:objects [{:kind :sphere} {:kind :box}]
                                   :render {:reflections 0}}"]
                  ["glow" "{:objects [{:kind :sphere} {:kind :box}]
                            :render {:reflections 2 :glow true}}"]
                  ["view" base {:view :normals}]
                  ["uber" base {:uber? true}]])]
          (let [k (key-of source options)]
            (assert (not= base-key k) (.. what " did not change the key: " k))))))

    (it "does not change with values"
      (fn []
        (each [_ source
               (ipairs
                 ["{:objects [{:kind :sphere :pos [9 9 9] :color [0 1 0] :radius 7}
                              {:kind :box :size [3 4 5] :pos [-1 -1 -1]}]
                    :render {:reflections 2}}"
                  "{:objects [{:kind :sphere} {:kind :box}]
                    :light {:pos [100 -5 3]} :render {:reflections 2 :epsilon 0.01}}"
                  "{:objects [{:kind :sphere} {:kind :box}]
                    :render {:reflections 16 :max-steps 20 :draw-distance 5}
                    :camera {:pos [1 2 3] :yaw 3 :fov 20}
                    :environment [0 0 0]}"])]
          (assert.are.equal base-key (key-of source)))))

    (it "is the same for any reflection count above zero"
      (fn []
        (assert.are.equal (key-of "{:objects [] :render {:reflections 1}}")
                          (key-of "{:objects [] :render {:reflections 16}}"))))))

(describe "plan: uniform budget"
  (fn []
    ;; A sphere takes 2 vectors (its place and radius, its material) and 32 are
    ;; reserved: (4096 - 32) / 2 = 2032 spheres fit in uniform arrays. (From 16 on
    ;; they form a field in textures, and from grid.min-members on a group has a
    ;; grid and its rows in a texture, neither with such a budget: :field? false and
    ;; :grids? false keep them in uniforms here; see field_spec and grid_spec.)
    (local most (math.floor (/ (- plan.default-uniform-limit plan.fixed-uniform-vectors) 2)))

    (it "has the documented limits"
      (fn []
        (assert.are.equal 4096 plan.default-uniform-limit)
        (assert.are.equal 32 plan.fixed-uniform-vectors)
        (assert.are.equal 2032 most)))

    (it "plans the largest number of spheres that fits"
      (fn []
        (let [p (assert (plan.scene->plan (spheres most) {:field? false :grids? false}))]
          (assert.are.equal 4096 p.uniform-vectors)
          (assert.are.equal most (. p.tape.objects 1 :instances :count))
          (assert.truthy (p.key:find (.. "tape=group:" most "[translate( sphere ) ;] rows:0") 1 true)))))

    (it "refuses one more sphere with a message naming the file and the budget"
      (fn []
        (let [(p err) (plan.scene->plan (spheres (+ most 1)) {:field? false :grids? false})]
          (assert.is_nil p)
          (assert.are.equal
            (.. "t.fnl: objects: the scene needs 4098 uniform vectors but the driver allows "
                "4096 (32 are reserved); remove objects worth 2 vectors (a sphere takes 2)")
            err)
          (assert.truthy (err:find "uniform vectors" 1 true))
          ;; As a field they fit, and as a group with a grid.
          (assert.truthy (. (assert (plan.scene->plan (spheres (+ most 1)))) :field))
          (let [p (assert (plan.scene->plan (spheres (+ most 1)) {:field? false}))]
            (assert.are.equal 1 (length p.grids.list))
            (assert.is_true (< p.uniform-vectors 100))))))

    (it "honours the :uniform-limit option"
      (fn []
        ;; The seed needs 48 vectors.
        (assert.truthy (plan.scene->plan seed {:uniform-limit 48}))
        (let [(p err) (plan.scene->plan seed {:uniform-limit 47})]
          (assert.is_nil p)
          (assert.are.equal
            (.. "scenes/seed.fnl: objects: the scene needs 48 uniform vectors but the driver "
                "allows 47 (32 are reserved); remove objects worth 1 vectors "
                "(a box takes 3, a sphere takes 2, a plane takes 3)")
            err))
        (let [(p err) (plan.scene->plan (spheres 10) {:uniform-limit 40})]
          (assert.is_nil p)
          (assert.truthy (err:find "needs 52 uniform vectors" 1 true)))))

    (it "counts an uber plan's objects as a specialized one's"
      (fn []
        (let [p (plan-of "{:objects [{:kind :sphere}]}" {:uber? true})]
          (assert.are.equal (+ 32 2) p.uniform-vectors))
        (let [(p err) (plan.scene->plan (load "{:objects [{:kind :sphere}]}") {:uber? true :uniform-limit 33})]
          (assert.is_nil p)
          (assert.truthy (err:find "needs 34 uniform vectors" 1 true)))))))

(describe "plan: renderer options"
  (fn []
    (it "copies uniforms once per pixel on software renderers only"
      (fn []
        (each [_ name (ipairs ["llvmpipe (LLVM 15.0.6, 256 bits)" "softpipe" "Mesa swrast"
                               "Google SwiftShader" "GDI Generic"])]
          (assert.is_true (plan.software-renderer? name) name)
          (assert.is_true (. (plan.renderer-options name) :load-once?) name))
        (each [_ name (ipairs ["NVIDIA H100 80GB HBM3/PCIe/SSE2"
                               "AMD Radeon RX 7900 XTX (radeonsi, navi31, LLVM 15.0.6, DRM 3.54)"
                               "Mesa Intel(R) UHD Graphics 620 (KBL GT2)" "Apple M2"])]
          (assert.is_false (plan.software-renderer? name) name)
          (assert.is_false (. (plan.renderer-options name) :load-once?) name))))

    (it "keeps what the caller chose and the caller's table"
      (fn []
        (let [given {:view :normals :load-once? true}
              options (plan.renderer-options "NVIDIA H100" given)]
          (assert.is_true options.load-once?)
          (assert.equal :normals options.view)
          (assert.is_false (rawequal given options))
          (assert.is_false (. (plan.renderer-options "llvmpipe" {:load-once? false}) :load-once?)))))

    (it "gives a GPU's plan a key of its own"
      (fn []
        (let [src "{:objects [{:kind :sphere}]}"]
          (assert.not_equal (key-of src (plan.renderer-options "llvmpipe"))
                            (key-of src (plan.renderer-options "NVIDIA H100"))))))))

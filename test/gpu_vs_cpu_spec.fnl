;; Every scene in scenes/, rendered by the generated GLSL through OSMesa, against the CPU
;; reference marcher (src/reference.fnl) on sampled pixels: a jittered grid plus pixels
;; beside silhouettes, shadow edges and reflected edges.

;; The budgets, and what they were measured on: test/support/budgets.fnl (the tape
;; interpreter's pictures are held to the same ones: test/interpret_gpu_spec.fnl).
(local {: budget-for} (require :test.support.budgets))

(local headless (require :src.backend.headless))
(local codegen (require :src.render.codegen))
(local {: marched-mix} (require :test.support.scenes))
(local {: scene-files : prepare : gpu-render : compare-image : passes?
        : describe-failures : report-line} (require :test.support.gpu-check))

;; The views besides :shaded, each checked on every scene too.
(local other-views [:normals :glow :heat])

(describe "GPU against the CPU reference"
  (fn []
    (let [(ctx why) (headless.context)]
      (if (not ctx)
          (pending (.. "OSMesa is not available: " (tostring why)))
          (let [prepared-cache {}
                prepared-for (fn [file view]
                               (let [key (.. file " " view)]
                                 (when (= nil (. prepared-cache key))
                                   (tset prepared-cache key (prepare file {: view})))
                                 (. prepared-cache key)))
                check (fn [file view]
                        (let [prepared (prepared-for file view)
                              name prepared.scene.name
                              label (if (= view :shaded) name (.. name " " view))
                              (budget measured?) (budget-for name view)
                              st (compare-image prepared (gpu-render ctx prepared))]
                          (print (report-line label st))
                          (assert.is_true (>= st.count 256)
                                          (.. file ": only " st.count " pixels sampled"))
                          (assert.is_true (passes? st budget)
                                          (describe-failures (.. "scene " label) st budget
                                                             measured?))))
                ;; The GPU picture `st` (compared), reported as `label`, must pass `budget`.
                passes-as-reference (fn [label st budget]
                                      (print (report-line label st))
                                      (assert.is_true (passes? st budget)
                                                      (describe-failures label st budget)))
                ;; The GPU picture of `prepared` drawn by `shader` with `pattern` put in
                ;; once by `replacement` (a fault the CPU reference lacks), reported as
                ;; `label`, must fail `budget`.
                fails-broken (fn [prepared budget label shader pattern replacement]
                               (let [(source n) (shader:gsub pattern replacement)
                                     _ (assert.are.equal 1 n)
                                     st (compare-image prepared (gpu-render ctx prepared {:source #source}))]
                                 (print (report-line label st))
                                 (assert.is_false (passes? st budget))))]
            (it "finds the scenes"
              (fn []
                (let [files {}]
                  (each [_ f (ipairs (scene-files))] (tset files f true))
                  (assert.is_true (. files "scenes/seed.fnl")))))

            (each [_ file (ipairs (scene-files))]
              (it (.. "matches the reference on " file)
                (fn [] (check file :shaded)))
              (it (.. "matches the reference on " file " in the "
                      (table.concat other-views ", ") " views")
                (fn [] (each [_ view (ipairs other-views)] (check file view)))))

            (it "fails the seed scene when the GLSL box distance is broken"
              (fn []
                (let [prepared (prepared-for "scenes/seed.fnl" :shaded)
                      budget (budget-for :seed :shaded)]
                  ;; Interior distance negated: faces facing +x, +y or +z get wrong
                  ;; normals from the one-sided differences, which reach inside. (The
                  ;; box's GLSL is the translator's, from its :fennel text: the
                  ;; interior term is min(max(max(qx, qy), qz), 0.0) in its names.)
                  (fails-broken prepared budget "seed, broken -min" (codegen.shader prepared.plan :core)
                                "%+ (min%(max%(max%(v%d+, v%d+%), v%d+%), 0%.0%))"
                                "+ -%1")
                  ;; A sign flipped in the translation every object is placed by:
                  ;; opTranslate(p, c) gives p + c, and each object moves to -c.
                  (fails-broken prepared budget "seed, broken p+c" (codegen.shader prepared.plan :core)
                                "return p %- t;" "return p + t;"))))

            (it "fails a scene of exact normals when the shader's box or sphere gradient is broken"
              (fn []
                ;; flat: boxes, spheres and a floor under the default normals, each
                ;; object's own gradient in closed form (normal-exact.glsl).
                (let [prepared (prepared-for "scenes/flat.fnl" :shaded)
                      budget (budget-for :flat :shaded)
                      shader (codegen.shader prepared.plan :core)]
                  (assert.is_truthy (shader:find "n = gradBox(p1, " 1 true))
                  (each [_ [label pattern replacement]
                         (ipairs [;; Outside, the sign of the offset lost: faces toward
                                  ;; -x, -y or -z point the other way. (Hit points lie on
                                  ;; or just outside the surface, so this is the branch
                                  ;; that draws them.)
                                  ["box faces" "vec3 g = max%(e, 0%.0%) %* s;" "vec3 g = max(e, 0.0);"]
                                  ;; A sphere's normal from the wrong point.
                                  ["sphere" "return len > 0%.0 %? p / len" "return len > 0.0 ? -p / len"]])]
                    (fails-broken prepared budget (.. "flat, broken " label " gradient")
                                  shader pattern replacement)))))

            (it "fails the seed scene when a uniform array is sent in the wrong order"
              (fn []
                (let [prepared (prepared-for "scenes/seed.fnl" :shaded)
                      budget (budget-for :seed :shaded)
                      ;; The objects' rows (placements, sizes, materials) last first.
                      reverse-rows
                      (fn [us]
                        (icollect [_ u (ipairs us)]
                          (if (= u.name "uTape")
                              ;; (On llvmpipe the rows travel as a texture.)
                              (let [vals []
                                    rows (or u.values u.texture.data)
                                    n (/ (length rows) 4)]
                                (assert.is_true (> n 1))
                                (for [i (- n 1) 0 -1]
                                  (for [c 1 4]
                                    (table.insert vals (. rows (+ (* i 4) c)))))
                                (if u.texture
                                    {:name u.name :type u.type :count u.count
                                     :texture {:width u.texture.width :height u.texture.height
                                               :data vals}}
                                    {:name u.name :type u.type :count u.count :values vals}))
                              u)))
                      st (compare-image prepared (gpu-render ctx prepared
                                                             {:uniforms reverse-rows}))]
                  (print (report-line "seed, rows reversed" st))
                  (assert.is_false (passes? st budget)))))

            (it "fails a bounded scene when the shader's bounds or planes are broken"
              (fn []
                ;; gallery marches with bounds (src/render/bounds.fnl); the reference
                ;; follows the same rules, so breaking them in the GLSL alone must show.
                (let [prepared (prepared-for "scenes/gallery.fnl" :shaded)
                      budget (budget-for :gallery :shaded)
                      shader (codegen.shader prepared.plan :core)]
                  (assert.truthy prepared.plan.bounds)
                  (each [_ [label pattern replacement]
                         (ipairs [["bounding spheres at half their radius"
                                   "float disc = uBounds%[i%]%.w %* uBounds%[i%]%.w"
                                   "float disc = 0.25 * uBounds[i].w * uBounds[i].w"]
                                  ["the plane met 10% too far"
                                   "t = min%(t, %-s / v%);"
                                   "t = min(t, 1.1 * -s / v);"]])]
                    (fails-broken prepared budget (.. "gallery, " label) shader pattern replacement)))))

            (it "ends shadow rays at the light in a bounded scene, and catches a shader that does not"
              (fn []
                ;; A box above the light: with bounds it casts no shadow on the floor
                ;; below the light; the article's shadow ray (to the draw distance) would.
                (with-open [f (assert (io.open "test/out/light-below-box.fnl" :wb))]
                  (f:write "{:camera {:pos [0 -12 4] :yaw 90 :pitch -15 :fov 60}
                             :light {:pos [0 0 5]}
                             :render {:reflections 0}
                             :objects [{:kind :box :size [20 20 1] :pos [0 0 9]}
                                       {:kind :sphere :radius 1 :pos [3 0 1]}
                                       {:kind :plane :height 0 :color [0.8 0.8 0.8]}]}"))
                (let [prepared (prepare "test/out/light-below-box.fnl" {:view :shaded})
                      budget {:over 2 :max 40}
                      shader (codegen.shader prepared.plan :core)]
                  (assert.truthy prepared.plan.bounds)
                  (assert.is_true (passes? (compare-image prepared (gpu-render ctx prepared)) budget))
                  ;; The article's shadow ray in the shader only: to the draw distance,
                  ;; and any hit shadows.
                  (let [(source n) (-> shader
                                       (: :gsub "raymarchTo%(p %+ n %* %(2%.0 %* normalDelta%(p%)%), l, reach,"
                                          "raymarchTo(p + n * (2.0 * normalDelta(p)), l, uDrawDist,")
                                       (: :gsub "if %(ts < reach%)" "if (ts < uDrawDist)"))
                        _ (assert.are.equal 1 n)
                        st (compare-image prepared (gpu-render ctx prepared {:source #source}))]
                    (print (report-line "light below a box, shadow past the light" st))
                    (assert.is_false (passes? st budget))))))

            (it "walks a field beside other objects (a tree, a ground plane) as the reference does"
              (fn []
                ;; The general walk (march.glsl's step-field): the torus (a tree: in a
                ;; union, not a marched member) is sphere-traced alongside the field's
                ;; cells. Measured: 1 of 512 pixels over, max
                ;; 22.2/255 (a flipped silhouette pixel; the same before the march's
                ;; forms became one chunk); the budget allows one or two of those.
                (with-open [f (assert (io.open "test/out/field-beside-torus.fnl" :wb))]
                  (f:write "(var seed 7)
(fn rnd [] (set seed (% (+ (* seed 1103515245) 12345) 2147483648)) (/ seed 2147483648))
(local objects [{:kind :plane :height 0 :color [0.6 0.6 0.6]}
                {:kind :union :pos [0 0 4] :color [0.9 0.6 0.2]
                 :children [{:kind :torus :radius 3 :thickness 0.8}]}])
(for [i 1 300]
  (let [x (+ -20 (* 40 (rnd))) y (+ -20 (* 40 (rnd))) z (+ 0.5 (* 10 (rnd)))
        r (+ 0.2 (* 0.5 (rnd)))]
    (table.insert objects (if (= 0 (% i 2))
                              {:kind :box :pos [x y z] :size [r (* 2 r) r] :color [(rnd) (rnd) (rnd)]}
                              {:kind :sphere :pos [x y z] :radius r :color [(rnd) (rnd) (rnd)]}))))
{:camera {:pos [0 -35 12] :yaw 90 :pitch 15 :fov 60}
 :light {:pos [-20 -30 40]}
 :render {:shadows true :reflections 2}
 :objects objects}"))
                (let [prepared (prepare "test/out/field-beside-torus.fnl" {:view :shaded})
                      st (compare-image prepared (gpu-render ctx prepared))]
                  (assert.truthy prepared.plan.field)
                  (assert.are.equal 1 prepared.plan.bounds.count)
                  (passes-as-reference "field beside a torus" st {:over 2 :max 40}))))

            (it "walks a field of marched members (tori, capsules) as the reference does"
              (fn []
                ;; The lean walk (march.glsl's step-cells) through spheres, rotated tori
                ;; and capsules: each torus and capsule sphere-traced alone in its frame
                ;; (field-primitives.glsl's fieldMarchedEntry, field.fnl's
                ;; marched-entry), normals by differences. Measured: max 0.7/255, 0 over
                ;; (seed 1); with each member met unrotated (its quaternion ignored) 109
                ;; over, max 186.2.
                (with-open [f (assert (io.open "test/out/field-marched.fnl" :wb))]
                  (f:write (marched-mix 300 "{:shadows true :reflections 1}")))
                (let [prepared (prepare "test/out/field-marched.fnl" {:view :shaded})
                      st (compare-image prepared (gpu-render ctx prepared))]
                  (assert.are.same [:torus :capsule] prepared.plan.field.kinds.marched)
                  (assert.are.equal 0 prepared.plan.bounds.count)
                  (passes-as-reference "field of marched members" st {:over 2 :max 40}))))

            (it "draws every bounded primitive as a field's marched member as the reference does"
              (fn []
                ;; Four rotated copies of each primitive a field can hold (its defaults,
                ;; in rows over a floor): one kind code each, each kind's arguments read
                ;; from its packed numbers (codegen's marched-args). Measured: max
                ;; 1.3/255, 0 over; with each number read from the next one's place 331
                ;; over.
                (let [primitives (require :src.sdf.primitives)
                      field (require :src.render.field)
                      kinds (icollect [_ d (ipairs primitives.all)]
                              (let [o {:kind d.kind :tree (collect [_ p (ipairs d.params)] p.name p.default)}]
                                (set o.tree.kind d.kind)
                                (when (field.member? o) d.kind)))
                      objects (icollect [i kind (ipairs kinds)]
                                (table.concat
                                 (fcollect [j 1 4]
                                   (string.format "{:kind :%s :pos [%d %d %g] :rotate [%d %d %d] :color [%.2f %.2f %.2f]}"
                                                  kind (- (* 3 (% i 9)) 12) (- (* 3 (math.floor (/ i 9))) (* 9 (- j 2)))
                                                  1.2 (* 23 (+ i j)) (* 37 j) (* 11 i)
                                                  (/ (% i 5) 5) (/ (% j 3) 3) 0.6))
                                 " "))]
                  (with-open [f (assert (io.open "test/out/field-every-kind.fnl" :wb))]
                    (f:write (.. "{:camera {:pos [0 -30 14] :yaw 90 :pitch 25 :fov 60}
 :light {:pos [-20 -30 40]}
 :render {:shadows true :reflections 1}
 :objects [{:kind :plane :height 0 :color [0.6 0.6 0.6]} " (table.concat objects " ") "]}")))
                  (let [prepared (prepare "test/out/field-every-kind.fnl" {:view :shaded})
                        st (compare-image prepared (gpu-render ctx prepared))]
                    (assert.are.same kinds prepared.plan.field.kinds.marched)
                    (assert.is_true (>= (length kinds) 26))
                    (passes-as-reference "every primitive marched" st {:over 2 :max 40})))))

            (it "walks a field of spheres as the reference does, and catches a walk that skips lists"
              (fn []
                ;; march.glsl's step-spheres: 2000 spheres of radius 0.2 to 0.7, so that
                ;; many cells list several (a turn per sphere). A walk that never
                ;; starts a cell's list misses the spheres of those cells.
                (with-open [f (assert (io.open "test/out/field-of-spheres.fnl" :wb))]
                  (f:write "(var seed 7)
(fn rnd [] (set seed (% (+ (* seed 1103515245) 12345) 2147483648)) (/ seed 2147483648))
(local objects [{:kind :plane :height 0 :color [0.6 0.6 0.6]}])
(for [i 1 2000]
  (let [x (+ -20 (* 40 (rnd))) y (+ -20 (* 40 (rnd))) z (+ 0.5 (* 10 (rnd)))]
    (table.insert objects {:kind :sphere :pos [x y z] :radius (+ 0.2 (* 0.5 (rnd)))
                           :color [(rnd) (rnd) (rnd)]})))
{:camera {:pos [0 -35 12] :yaw 90 :pitch 15 :fov 60}
 :light {:pos [-20 -30 40]}
 :render {:shadows true :reflections 1}
 :objects objects}"))
                (let [prepared (prepare "test/out/field-of-spheres.fnl" {:view :shaded})
                      budget {:over 2 :max 40}
                      st (compare-image prepared (gpu-render ctx prepared))]
                  (assert.is_true prepared.plan.field.walk?)
                  (passes-as-reference "field of spheres" st budget)
                  (fails-broken prepared budget "field of spheres, lists never started"
                                (codegen.shader prepared.plan :core)
                                "bool starts = !inList && texel%.w < 0%.0;"
                                "bool starts = false;")
                  ;; A walk that leaves every list after the sphere about its
                  ;; spheres misses them.
                  (fails-broken prepared budget "field of spheres, lists left at their bound"
                                (codegen.shader prepared.plan :core)
                                "bool past = bound && entry > min%(tNext%.x, min%(tNext%.y, tNext%.z%)%);"
                                "bool past = bound;")
                  ;; A walk that jumps one cell past an empty cell's clearance passes
                  ;; over cells that list spheres.
                  (fails-broken prepared budget "field of spheres, jumps a cell too far"
                                (codegen.shader prepared.plan :core)
                                "%? max%(k %- 1%.0, 0%.0%) :" "? k :"))))

            (it "renders 100,000 spheres as the reference does"
              (fn []
                ;; test/fixtures/spheres-100000.fnl: a field of 100,000 (grid 256 x 256 x 3,
                ;; 355,083 records). Measured: 0 pixels over, max 0.5/255; the budget
                ;; allows a flipped silhouette pixel or two.
                (let [prepared (prepare "test/fixtures/spheres-100000.fnl" {:view :shaded :size [160 90]})
                      st (compare-image prepared (gpu-render ctx prepared))]
                  (assert.are.equal 100000 prepared.plan.field.count)
                  (passes-as-reference "100,000 spheres" st {:over 2 :max 40}))))

            (it "walks a field's grid as the reference does, and catches a walk that skips cells"
              (fn []
                ;; scenes/city.fnl: 10,000 towers and domes in a field (see field_spec).
                ;; A walk that never moves on along x keeps testing the cell it entered
                ;; and misses the towers beyond it.
                (let [prepared (prepared-for "scenes/city.fnl" :shaded)
                      budget (budget-for "city" :shaded)]
                  (assert.truthy prepared.plan.field)
                  (fails-broken prepared budget "city, walk without x steps"
                                (codegen.shader prepared.plan :core)
                                "index %+= int%(dot%(fieldNextWall%(tNext, tDelta%), stride%)%);"
                                "index += int(dot(fieldNextWall(tNext, tDelta) * vec3(0.0, 1.0, 1.0), stride));")))))))))

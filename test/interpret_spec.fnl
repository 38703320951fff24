;; tier: fast
;; The tape interpreter (issue 42, src/sdf/interpret.fnl): a scene's tape as a program
;; in a texture, run by one shader for every tape of its instruction set. Here what
;; needs no GPU: one shader for a structural edit, the instruction set, refusals,
;; registers, and the program run on the CPU against the tape's own evaluators
;; (test/support/program.fnl). Its pictures: test/interpret_gpu_spec.fnl.

(local load (require :src.scene.load))
(local plan-mod (require :src.render.plan))
(local codegen (require :src.render.codegen))
(local uniforms (require :src.render.uniforms))
(local camera (require :src.render.camera))
(local interpret (require :src.sdf.interpret))

(fn plan-of [text ?options]
  ;; The plan (or nil and why) and the scene of scene file text `text`.
  (let [(s err) (load.load-string text "interpret.fnl")
        _ (assert s err)
        (p perr) (plan-mod.scene->plan s ?options)]
    (values p perr s)))

(local two-objects
  "{:objects [{:kind :smooth-union :radius 0.3 :pos [0 0 1] :color [1 0.5 0.2]
               :children [{:kind :sphere :radius 1} {:kind :box :size [1.5 1.5 1.5] :pos [0.8 0 0]}]}
              {:kind :plane :normal [0 0 1] :height 0}]}")

;; A sphere added to the blend, and the ground's kind as a second object.
(local three-objects
  "{:objects [{:kind :smooth-union :radius 0.3 :pos [0 0 1] :color [1 0.5 0.2]
               :children [{:kind :sphere :radius 1} {:kind :box :size [1.5 1.5 1.5] :pos [0.8 0 0]}
                          {:kind :sphere :radius 0.4 :pos [0 0 1.2] :color [1 0 1]}]}
              {:kind :plane :normal [0 0 1] :height 0}
              {:kind :plane :normal [0 0 1] :height -2 :color [0 0 1]}]}")

;; Then a box, a torus and a twist of a capsule, each an object of its own: kinds
;; the scene did not call, but the catalogue holds.
(local other-kinds
  "{:objects [{:kind :smooth-union :radius 0.3 :pos [0 0 1] :color [1 0.5 0.2]
               :children [{:kind :sphere :radius 1} {:kind :box :size [1.5 1.5 1.5] :pos [0.8 0 0]}]}
              {:kind :plane :normal [0 0 1] :height 0}
              {:kind :box :size [0.5 0.5 0.5] :pos [2 2 0.25] :color [0 0 1]}
              {:kind :torus :radius 0.5 :thickness 0.1 :pos [-2 0 0.5]}
              {:kind :twist :angle 90 :pos [0 -2 0.5] :children [{:kind :capsule :a [0 0 0] :b [0 0 1] :radius 0.2}]}]}")

(describe "the tape interpreter"
  (fn []
    (it "draws a structural edit with the same shader: objects added of kinds the set holds"
      (fn []
        (let [a (plan-of two-objects {:interpret? true})
              b (plan-of three-objects {:interpret? true})
              ;; The compiled shaders differ, as they must.
              ca (plan-of two-objects)
              cb (plan-of three-objects)]
          (assert.are_not.equal ca.key cb.key)
          (assert.are.equal a.key b.key)
          (assert.are.equal (codegen.shader a :core) (codegen.shader b :core))
          ;; Other kinds, with the catalogue as the player holds it.
          (let [all (interpret.catalogue)
                (c cerr) (plan-of other-kinds {:interpret? true :instructions all})]
            (assert.is_truthy c cerr)
            (assert.are.equal (. (plan-of two-objects {:interpret? true :instructions all}) :key) c.key)
            ;; Objects that all have an exact normal (a sphere, the ground), where the
            ;; compiled shader takes normal-exact.glsl: the same shader too.
            (let [exact "{:objects [{:kind :sphere :radius 1 :pos [0 0 1]} {:kind :plane :normal [0 0 1] :height 0}]}"]
              (assert.is_true (. (plan-of exact) :exact-normals?))
              (assert.are.equal c.key (. (plan-of exact {:interpret? true :instructions all}) :key))))
          ;; What differs travels as the program and the rows: textures.
          (let [s (select 3 (plan-of three-objects))
                us (uniforms.pack s b (camera.from-scene s) 8 8)
                by-name (collect [_ u (ipairs us)] u.name u)]
            (assert.are.equal :texture (. by-name "uProgram" :type))
            (assert.are.equal :texture (. by-name "uTape" :type))
            (assert.are.equal 3 (. by-name "uProgram" :texture :data 1))))))

    (it "numbers its opcodes by a sorted set: the same set, the same text"
      (fn []
        (let [all (interpret.catalogue)
              keys (icollect [_ e (ipairs all)] e.key)
              sorted (doto (icollect [_ k (ipairs keys)] k) table.sort)]
          (assert.are.same sorted keys)
          ;; Every primitive and every operation is in the catalogue.
          (each [_ k (ipairs [:prim:sdSphere :prim:sdVesica :prim:sdLargeSphere :gradient:gradBox
                              :combine:opSmoothUnionExp :cells:opRepeat :cells:opPolar
                              :post:opTwistDistance :distance:opDisplace :point:opRotate])]
            (assert.is_truthy (accumulate [found? false _ key (ipairs keys)] (or found? (= key k)))
                              (.. k " missing")))
          ;; The interpreter's tapes take general forms (a plane, not the ground
          ;; form of one facing up; opRepeat, not one along x): every scene holds
          ;; nothing beyond the catalogue but its custom nodes' functions.
          (let [key (. (plan-of two-objects {:interpret? true :instructions all}) :key)]
            (assert.is_nil (key:find "prim:sdGround" 1 true))
            (assert.truthy (key:find "prim:sdPlane" 1 true))
            (assert.truthy (key:find "prim:sdVesica" 1 true)))
          (let [files (with-open [p (io.popen "ls scenes/*.fnl")] (icollect [l (p:lines)] l))
                held (collect [_ e (ipairs all)] e.key true)]
            (each [_ file (ipairs files)]
              (case (plan-mod.scene->plan (assert (load.load-file file))
                                          {:interpret? true :instructions all})
                p (let [iset (. (interpret.program-object p.tape) :set)
                        beyond (icollect [_ e (ipairs iset)]
                                 (when (not (. held e.key)) e.key))]
                    (if (= file "scenes/custom.fnl")
                        (assert.is_true (> (length beyond) 0))
                        (assert.are.same [] beyond file)))))))))

    (it "refuses what it cannot run, saying what"
      (fn []
        ;; A union of 40 children of one structure is a blend: one loop over their
        ;; rows (lower.fnl), which the interpreter has no instruction for.
        (let [kids (table.concat (fcollect [i 1 40]
                                   (.. "{:kind :sphere :radius 0.2 :pos [" (* 0.5 i) " 0 0]}")) " ")
              (p err) (plan-of (.. "{:objects [{:kind :union :children [" kids "]}]}")
                               {:interpret? true})]
          (assert.is_nil p)
          (assert.truthy (err:find "interpret.fnl: the interpreter cannot draw it: a union of many children of one structure" 1 true)
                         err))
        ;; Five repetitions one inside another: the shader's loop stack holds four.
        (let [nest (fn nest [n]
                     (if (= n 0) "{:kind :sphere :radius 0.2}"
                         (.. "{:kind :repeat :period [" (* n 3) " 0 0] :children [" (nest (- n 1)) "]}")))]
          (assert.is_truthy (plan-of (.. "{:objects [" (nest 4) "]}") {:interpret? true}))
          (let [(p err) (plan-of (.. "{:objects [" (nest 5) "]}") {:interpret? true})]
            (assert.is_nil p)
            (assert.truthy (err:find "repetitions nested more than 4 deep" 1 true) err)))
        ;; 1,025 objects the program would run: every step of every pixel would
        ;; visit each. (As a field, the spheres are walked through its grid: below.)
        (let [spheres (fcollect [i 1 1025] (.. "{:kind :sphere :radius 0.1 :pos [" i " 0 0]}"))
              text (.. "{:objects [" (table.concat spheres " ") "]}")
              (p err) (plan-of text {:interpret? true :field? false})]
          (assert.is_nil p)
          (assert.truthy (err:find "interpret.fnl: the interpreter cannot draw it: 1025 objects (at most 1024" 1 true)
                         err)
          (assert.is_truthy (plan-of text {:interpret? true})))))

    ;; llvmpipe ends all of a shader's loops after 65,535 turns in all (see
    ;; interpret.software-fits?): on a software renderer a longer program, or one
    ;; whose turns a still's rays multiply past the most, is refused, saying so.
    (it "counts its loop turns, and refuses on a software renderer what they would cut short"
      (fn []
        (let [tape-of #(. (interpret.program-object (. (plan-of $ {:interpret? true}) :tape)) :tape)
              spheres (fn [n] (.. "{:objects [" (table.concat (fcollect [i 1 n] (.. "{:kind :sphere :radius 0.1 :pos [" i " 0 0]}")) " ")
                                  "]}"))
              ;; A repetition: its cells and its body per cell visited.
              repeated "{:objects [{:kind :repeat :period [3 3 0] :count [2 2 0] :children [{:kind :sphere :radius 0.2}]}]}"
              one (interpret.loop-turns (tape-of (spheres 1)))
              ten (interpret.loop-turns (tape-of (spheres 10)))]
          (assert.is_true (> one 0))
          (assert.are.equal (* 10 one) ten)
          (assert.is_true (> (interpret.loop-turns (tape-of repeated)) one))
          (assert.is_true (interpret.software-fits? (tape-of (spheres 10))))
          (let [(fits? turns most) (interpret.software-fits? (tape-of (spheres 10)) 18)]
            (assert.is_false fits?)
            (assert.are.equal ten turns)
            (assert.is_true (< most ten))))
        (let [grid (assert (load.load-file "test/fixtures/grid-modern.fnl"))
              organic (assert (load.load-file "scenes/organic.fnl"))]
          ;; On a GPU (software? false), or not asked, the same scene is drawn.
          (assert.is_truthy (plan-mod.scene->plan grid {:interpret? true}))
          (assert.is_truthy (plan-mod.scene->plan grid {:interpret? true :software? false}))
          (let [(p err) (plan-mod.scene->plan grid {:interpret? true :software? true})]
            (assert.is_nil p)
            (assert.truthy (err:find "test/fixtures/grid%-modern%.fnl: the interpreter cannot draw it: its program takes %d+ loop turns a distance, and llvmpipe stops a shader.s loops after 65,535 turns in all")
                           err))
          ;; Organic's one ray a pixel fits; its 4 x 4 still's 18 do not.
          (assert.is_truthy (plan-mod.scene->plan organic {:interpret? true :software? true}))
          (let [(p err) (plan-mod.scene->plan organic {:interpret? true :software? true :samples 4})]
            (assert.is_nil p)
            (assert.truthy (err:find "for each of 18 rays a pixel" 1 true) err)))
        ;; renderer-options says which renderer is a software one.
        (assert.is_true (. (plan-mod.renderer-options "llvmpipe (LLVM 15.0.6, 256 bits)") :software?))
        (assert.is_false (. (plan-mod.renderer-options "NVIDIA H200/PCIe/SSE2") :software?))))

    (it "keeps a field (city's 10,000 blocks), numbering the program's objects after its members"
      (fn []
        (let [(s) (load.load-file "scenes/city.fnl")
              c (assert (plan-mod.scene->plan s {}))
              p (assert (plan-mod.scene->plan s {:interpret? true}))
              [field program] p.tape.objects]
          (assert.are.equal 2 (length p.tape.objects))
          (assert.are.equal :field field.strategy)
          (assert.are.equal :interpreted program.strategy)
          ;; The ground, after the 10,000 members, as in the compiled plan.
          (assert.are.equal 10000 program.id)
          (assert.are.equal (. c.tape.objects 2 :id) program.id)
          (assert.are.same c.field.kinds p.field.kinds)
          ;; mapObject, mapColor and the normals name the ground by its number,
          ;; the field's count read from a uniform.
          (let [src (assert (codegen.shader p :love))
                us (uniforms.pack s p (camera.from-scene s) 16 16)]
            (assert.truthy (src:find "gObject = uFieldCount + tapeObject;" 1 true))
            (assert.truthy (src:find "only - uFieldCount" 1 true))
            (assert.is_nil (src:find "[^%d.]10000[^%d.]"))
            (assert.are.same [10000] (. (icollect [_ u (ipairs us)] (when (= u.name "uFieldCount") u)) 1 :values))
            ;; The walk marches other objects when the bounds' image holds some.
            (assert.truthy (src:find "#define fieldOthers() (boundsCount() > 0)" 1 true)))
          ;; A block more (the field's count), or a second ground (the program's
          ;; objects): the same shader, where the compiled one changes. (A torus
          ;; would be a marched member: a new kind, a new shader.)
          (each [_ extra (ipairs ["{:kind :box :pos [0 0 1] :size [1 1 2]}"
                                  "{:kind :plane :height -1}"])]
            (let [text (.. "(let [scene (do " (with-open [f (io.open "scenes/city.fnl")] (f:read :*a))
                           "\n)] (table.insert scene.objects " extra ") scene)")
                  (s2) (load.load-string text "city.fnl")
                  p2 (assert (plan-mod.scene->plan s2 {:interpret? true}))
                  c2 (assert (plan-mod.scene->plan s2 {}))]
              (assert.are.equal p.key p2.key extra)
              (assert.are_not.equal c.key c2.key extra))))))

    (it "marches by the compiled form's bounds, from an image whose count is not in the text"
      (fn []
        (let [distance (require :src.reference.distance)
              all (interpret.catalogue)]
          (each [_ file (ipairs ["scenes/organic.fnl" "scenes/gallery.fnl" "scenes/lighting.fnl"])]
            (let [s (assert (load.load-file file))
                  ;; The compiled plan without grids or a field, which bound their
                  ;; members as one.
                  c (assert (plan-mod.scene->plan s {:grids? false :field? false}))
                  p (assert (plan-mod.scene->plan s {:interpret? true :instructions all}))
                  cam (camera.from-scene s)
                  by-name #(collect [_ u (ipairs (uniforms.pack s $ cam 64 56))] u.name u)
                  spheres (. (by-name c) "uBounds" :values)
                  image (. (by-name p) "uBounds" :texture)]
              (assert.are.same {:texture? true} p.bounds)
              (assert.are.equal (/ (length spheres) 4) (. image.data 1) file)
              (assert.are.same spheres (icollect [i v (ipairs image.data)] (when (> i 4) v)) file)
              ;; The CPU reference meets the same half-spaces in closed form.
              (assert.are.same (distance.half-spaces c) (distance.half-spaces p) file)
              (assert.is_true (accumulate [any? false _ h (pairs (distance.half-spaces p))] (or any? h)))
              (let [text (codegen.shader p :core)]
                (assert.truthy (text:find "boundsCount()" 1 true))
                (assert.truthy (text:find "tapePlanesHit(p, rd, t)" 1 true))
                (assert.is_nil (text:find "uBounds[" 1 true)))))
          ;; An object without a bound (an endless repetition): no bounds, as the
          ;; compiled form; the other shader text of the view.
          (let [endless "{:objects [{:kind :repeat :period [3 3 0] :children [{:kind :sphere :radius 0.5}]}]}"
                bounded "{:objects [{:kind :sphere :radius 0.5}]}"
                p (plan-of endless {:interpret? true :instructions all})]
            (assert.is_nil (. (plan-of endless) :bounds))
            (assert.is_nil p.bounds)
            (assert.are_not.equal p.key (. (plan-of bounded {:interpret? true :instructions all}) :key))))))

    ;; The program run on the CPU (test/support/program.fnl: the shader's tapeRun with
    ;; the descriptors' CPU forms) against the tape's own CPU evaluators (emit-lua),
    ;; both in double: the encoding alone is checked, under plain LuaJIT.
    (it "computes what the tape's CPU evaluators compute, in every scene it runs"
      (fn []
        (let [emit-lua (require :src.sdf.emit-lua)
              {: runner} (require :test.support.program)
              files (with-open [p (io.popen "ls scenes/*.fnl")] (icollect [l (p:lines)] l))]
          (var (seed checked half-spaces) (values 7 0 0))
          (fn rnd [] (set seed (% (+ (* seed 1103515245) 12345) 2147483648)) (/ seed 2147483648))
          (each [_ file (ipairs files)]
            (let [scene (assert (load.load-file file))]
              (case (plan-mod.scene->plan scene {:interpret? true})
                p (let [o (interpret.program-object p.tape)
                        ev (emit-lua.compile o.tape)
                        run (runner o)
                        members (interpret.members-of o.tape)]
                    (set checked (+ checked 1))
                    (for [_ 1 30]
                      (let [x (* 20 (- (rnd) 0.5)) y (* 20 (- (rnd) 0.5)) z (* 8 (rnd))
                            got (run x y z false true)
                            estimates (run x y z true false)]
                        (assert.are.equal (length ev.distance) (length got))
                        (each [k r (ipairs got)]
                          (let [at (string.format "%s object %d at %.3f %.3f %.3f" file k x y z)
                                [_ & material] [((. ev.material k) x y z)]]
                            (assert.are.equal ((. ev.distance k) x y z) r.d at)
                            (assert.are.equal ((. ev.estimate k) x y z) (. estimates k :d) at)
                            (each [j v (ipairs r.m)] (assert.are.equal (. material j) v at))
                            (assert.are.equal (= true (. members k :o :half-space?)) r.half-space? at)
                            (when r.half-space? (set half-spaces (+ half-spaces 1)))
                            (let [g (. ev.gradient k)]
                              (if g (assert.are.same [(g x y z)] r.gradient at)
                                  (assert.is_nil r.gradient at)))))))))))
          (assert.are.equal 15 checked)
          ;; The ground planes among them, marked for tapePlanesHit.
          (assert.is_true (> half-spaces 0))
          ;; A program whose first argument reads one float on is caught.
          (let [p (plan-of two-objects {:interpret? true})
                o (. p.tape.objects 1)
                ev (emit-lua.compile o.tape)
                data o.program.data
                first-arg (+ 1 (* 4 (+ 1 (* 3 o.program.objects) 2)))]
            (tset data first-arg (+ 1 (. data first-arg)))
            (let [got ((runner o) 0.3 0.2 1.1)]
              (assert.are_not.equal ((. ev.distance 1) 0.3 0.2 1.1) (. got 1 :d)))))))

    (it "keeps an object's registers few: dead ones are reused"
      (fn []
        ;; Twelve children of one smooth union: each is folded in right after its
        ;; code (lower.fnl), so its distance dies there.
        (let [children (table.concat (fcollect [i 1 12]
                                       (.. "{:kind :sphere :radius 0.3 :pos [" (* 0.5 i) " 0 0]}")) " ")
              p (plan-of (.. "{:objects [{:kind :smooth-union :radius 0.2 :children [" children "]}]}")
                         {:interpret? true})
              prog (. p.tape.objects 1 :program)]
          (assert.is_true (<= prog.registers.d 4) (.. "distance registers " prog.registers.d))
          (assert.is_true (<= prog.registers.p 3) (.. "point registers " prog.registers.p)))))))

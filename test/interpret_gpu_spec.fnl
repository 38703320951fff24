;; The tape interpreter's pictures (issue 42, src/sdf/interpret.fnl; what needs no GPU
;; is in test/interpret_spec.fnl): held to the compiled shader's GPU-against-CPU
;; budgets (test/support/budgets.fnl), through OSMesa, and a fault put into one of its
;; opcodes must break them; and in the player, a structural edit drawn by it.

(local headless (require :src.backend.headless))
(local codegen (require :src.render.codegen))
(local interpret (require :src.sdf.interpret))
(local {: budget-for} (require :test.support.budgets))
(local {: prepare : gpu-render : compare-image : passes? : describe-failures : report-line}
  (require :test.support.gpu-check))

;; The scenes at the budgets' size (256x224: test/support/gpu-check.fnl's, where they
;; were measured); the broken opcodes at 96x84, which still gives 512 sampled pixels:
;; llvmpipe runs every case of the interpreter's switch for every instruction (it
;; masks branches; it does not skip them), so a picture costs seconds.
(local small [96 84])

(describe "the tape interpreter's pictures"
  (fn []
    ;; The player, headless (`love . --edit-latency SCENE --interpret-check`): once the
    ;; interpreter's shader is built, a structural edit whose own shader never comes
    ;; (the helper held) is drawn by it from the next frame, alone, as the CPU
    ;; reference draws it; let go, the helper's shader takes over. On llvmpipe the
    ;; interpreter is slow (seconds a frame at 64x36: every case of its switch runs),
    ;; so this takes a minute or two; the player uses it only on a GPU.
    (it "draws a structural edit in the player by the interpreter, then by the scene's own shader"
      (fn []
        (let [{: edit-latency-check} (require :test.support.app)
              (verdict line) (edit-latency-check "scenes/organic.fnl" "--interpret-check"
                                                 "interpret check")]
          (if (= verdict :pending) (pending line) (assert.are.equal :ok verdict line)))))

    (let [(ctx why) (headless.context)]
      (if (not ctx)
          (it "draws scenes within the compiled shader's budgets"
            (fn [] (pending (.. "OSMesa is not available: " (tostring why)))))
          (let [prepared-for (fn [file view ?size]
                               (prepare file {: view :size ?size :plan {:interpret? true}}))
                check (fn [prepared label ?source]
                        (let [budget (budget-for prepared.scene.name (or prepared.plan.view :shaded))
                              st (compare-image prepared (gpu-render ctx prepared {:source ?source}))]
                          (print (report-line (.. "interpreted " label) st))
                          (values (passes? st budget) st budget)))]
            ;; Each scene calls different parts: seed (no object normals), organic
            ;; (smooth blends, displacement, Lipschitz division, far fields, guards),
            ;; twisted-tower (a twist's post step), flower (repetitions: the loop),
            ;; lighting (the modern model's two-row materials), custom (Fennel
            ;; functions, estimates), flat in the normals view (exact gradients),
            ;; gallery (an instance group), colonnade (repetitions whose neighbours
            ;; are drawn by their boxes), city (10,000 blocks in a field, the
            ;; ground interpreted after them). Every other scene passed too, once
            ;; (docs/benchmarks.md).
            (each [_ [file view] (ipairs [["scenes/seed.fnl" :shaded] ["scenes/organic.fnl" :shaded]
                                          ["scenes/twisted-tower.fnl" :shaded]
                                          ["scenes/flower.fnl" :shaded] ["scenes/lighting.fnl" :shaded]
                                          ["scenes/custom.fnl" :shaded] ["scenes/flat.fnl" :normals]
                                          ["scenes/gallery.fnl" :shaded] ["scenes/colonnade.fnl" :shaded]
                                          ["scenes/city.fnl" :shaded]])]
              (it (.. "draws " file " (" view ") within the compiled shader's budget")
                (fn []
                  (let [prepared (prepared-for file view)
                        (ok? st budget) (check prepared (.. file " " view))]
                    (assert.are.equal :interpreted
                                      (. (interpret.program-object prepared.plan.tape) :strategy))
                    (assert.are.equal (if prepared.plan.field 2 1) (length prepared.plan.tape.objects))
                    (assert.is_true ok? (describe-failures (.. "interpreted " file) st budget true))))))

            ;; A GPU's plan reads uniforms where it uses them (plan.renderer-options);
            ;; the interpreter's textures are the same there.
            (it "draws in a GPU's form too (uniforms read where used)"
              (fn []
                (let [prepared (prepare "scenes/organic.fnl"
                                        {:size small :plan {:interpret? true :load-once? false}})
                      (ok? st budget) (check prepared "scenes/organic.fnl, a GPU's form")]
                  (assert.is_false prepared.plan.load-once?)
                  (assert.is_true ok? (describe-failures "interpreted organic, a GPU's form" st budget true)))))

            ;; 600 spheres of one structure (an instance group) on a floor: the
            ;; program takes 10 lines of its texture and the rows 2 (1,024 texels a
            ;; line), each member reads its own rows. Plain diffuse spheres, no
            ;; mirror: measured over 0, max 0.2/255; one grazing flip allowed.
            (it "draws 600 objects, its program and rows over several lines of their textures"
              (fn []
                (let [path (.. (os.tmpname) ".fnl")
                      spheres (fcollect [k 0 599]
                                (let [i (math.floor (/ k 20)) j (% k 20)]
                                  (string.format "{:kind :sphere :radius %.2f :pos [%.1f %.1f 0.3] :color [%.2f 0.5 %.2f]}"
                                                 (+ 0.2 (* 0.05 (% (+ i j) 3))) (- (* i 0.8) 12) (- (* j 0.8) 8)
                                                 (/ i 30) (/ j 20))))]
                  (with-open [f (io.open path "w")]
                    (f:write "{:camera {:pos [0 -22 9] :yaw 90 :pitch -20 :fov 60} :render {:reflections 0}\n"
                             " :objects [{:kind :plane :height 0 :color [0.6 0.6 0.6]}\n"
                             (table.concat spheres "\n") "]}\n"))
                  (let [prepared (prepared-for path :shaded [64 36])
                        o (. prepared.plan.tape.objects 1)
                        st (compare-image prepared (gpu-render ctx prepared))]
                    (os.remove path)
                    (print (report-line "interpreted 600 spheres" st))
                    (assert.are.equal 601 o.program.objects)
                    (assert.is_true (> o.program.height 1))
                    (assert.is_true (> (+ (length o.tape.rows) (length o.tape.instances.rows)) 1024))
                    (assert.is_true (passes? st {:over 1 :max 40})
                                    (describe-failures "600 spheres" st {:over 1 :max 40} true))))))

            (it "fails when an opcode is broken: the far field, a repetition's loop, a material"
              (fn []
                (each [_ [file pattern replacement]
                       (ipairs [;; The far field as a min: the box's distance wins far away.
                                ["scenes/organic.fnl" "gTapeD%[r0%] = max%(gTapeD%[r1%], gTapeD%[r2%]%)"
                                 "gTapeD[r0] = min(gTapeD[r1], gTapeD[r2])"]
                                ;; A repetition's cells each one off.
                                ["scenes/flower.fnl" ", loopCell%[depth %- 1%]%);"
                                 ", loopCell[depth - 1] + 1);"]
                                ;; A material read one row off.
                                ["scenes/lighting.fnl" "mat2x4%(tapeRowAt%(row%), tapeRowAt%(row %+ 4%)%)"
                                 "mat2x4(tapeRowAt(row + 4), tapeRowAt(row))"]])]
                  (let [prepared (prepared-for file :shaded small)
                        (broken n) (: (codegen.shader prepared.plan :core) :gsub pattern replacement)]
                    (assert.is_true (>= n 1))
                    (assert.is_false (check prepared (.. file " broken") #broken)))))))))))

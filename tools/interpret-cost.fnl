;; What the tape interpreter costs against the compiled shader on this machine's
;; OpenGL (OSMesa: llvmpipe here): for SCENE at WxH, the compile, the first frame
;; (llvmpipe builds the code at the first draw) and the median of 3 frames, of the
;; compiled shader, the interpreter holding the scene's own functions, and the one
;; holding the catalogue (every kind, as the player's). Wall clock from `date`.
;;   MESA_SHADER_CACHE_DISABLE=true luajit tools/fnl.lua tools/interpret-cost.fnl SCENE W H
(local headless (require :src.backend.headless))
(local load (require :src.scene.load))
(local plan-mod (require :src.render.plan))
(local codegen (require :src.render.codegen))
(local uniforms (require :src.render.uniforms))
(local camera (require :src.render.camera))
(local interpret (require :src.sdf.interpret))
(local ctx (assert (headless.context)))
(local [file w h] arg)
(local W (tonumber w)) (local H (tonumber h))
(local scene (assert (load.load-file file)))
(local cam (camera.from-scene scene))
(local clock (fn [] (let [f (io.popen "date +%s.%N")] (let [t (tonumber (f:read "*a"))] (f:close) t))))
(each [_ [label opts] (ipairs [["compiled" {}] ["interpreted, own set" {:interpret? true}]
                               ["interpreted, catalogue" {:interpret? true :instructions (interpret.catalogue)}]])]
  (let [p (assert (plan-mod.scene->plan scene opts))
        src (codegen.shader p :core)
        us (uniforms.pack scene p cam W H)
        t0 (clock)
        prog (assert (headless.compile ctx src))
        t1 (clock)
        _ (headless.render ctx prog {:width W :height H :uniforms us})
        t2 (clock)
        times (fcollect [i 1 3] (let [a (clock)] (headless.render ctx prog {:width W :height H :uniforms us}) (- (clock) a)))]
    (table.sort times)
    (print (string.format "%s %s %dx%d: compile %.0f ms, first frame %.0f ms, frame %.0f ms (median of 3)%s"
                          file label W H (* 1000 (- t1 t0)) (* 1000 (- t2 t1)) (* 1000 (. times 2))
                          (if opts.interpret? (.. ", " (length (. (interpret.program-object p.tape) :set)) " functions") "")))))

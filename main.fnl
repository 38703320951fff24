;; The LÖVE app: parses the command line, then either plays a scene interactively or
;; runs one command-line mode (render, print-shader, bench) and exits.

(local cli (require :src.cli))

(fn fail! [message]
  (io.stderr:write (.. "error: " message "\n"))
  (love.event.quit 1))

(fn print-shader [o]
  (let [frame (require :src.frame)
        codegen (require :src.codegen)
        (scene err) (frame.load-scene o.scene)]
    (if (not scene) (fail! err)
        (let [(plan perr) (frame.plan-for scene {:view o.view})]
          (if (not plan) (fail! perr)
              (do (io.write (codegen.shader plan (or o.target :love)))
                  (love.event.quit 0)))))))

(fn render [o]
  (let [frame (require :src.frame)
        gpu (require :src.gpu)
        camera (require :src.camera)
        (scene err) (frame.load-scene o.scene)]
    (if (not scene) (fail! err)
        (let [(plan perr) (frame.plan-for scene {:view o.view})
              [w h] (or o.size [512 448])]
          (if (not plan) (fail! perr)
              (let [canvas (love.graphics.newCanvas w h)
                    (ok? rerr) (frame.render-to-canvas! (gpu.new-cache) canvas scene plan
                                                        (camera.from-scene scene))]
                (if (not ok?) (fail! rerr)
                    (case (frame.write-png canvas o.out)
                      true (do (print (.. "wrote " o.out " (" w "x" h ")"))
                               (love.event.quit 0))
                      (_ werr) (fail! werr)))))))))

(fn bench [o]
  (let [bench-mod (require :src.bench)]
    (case (bench-mod.run-scene o)
      true (love.event.quit 0)
      (_ err) (fail! err))))

(fn bench-report [o]
  (let [bench-mod (require :src.bench)]
    (case (bench-mod.report o)
      true (love.event.quit 0)
      (_ err) (fail! err))))

(fn soak [o]
  (let [soak-mod (require :src.soak)]
    (case (soak-mod.run o)
      true (love.event.quit 0)
      (_ err) (fail! err))))

(fn play [o]
  (let [play-mod (require :src.play)]
    (play-mod.start! o)))

(local modes {:print-shader print-shader :render render :bench bench
              :bench-report bench-report :soak soak :play play})

(fn headless-error-handler [message]
  ;; Outside play mode nobody looks at LÖVE's error screen, and in a script or CI it
  ;; would wait forever: print the error and exit non-zero instead.
  (io.stderr:write (.. "error: " (debug.traceback (tostring message) 2) "\n"))
  (os.exit 1))

(fn love.load [args]
  (case (cli.parse (or args []))
    o (let [run (. modes o.mode)]
        ;; Command-line modes must never stop on LÖVE's error screen: a script waits on
        ;; them. Report the error and exit non-zero instead.
        (when (or (not= o.mode :play) o.shot)
          (set love.errorhandler headless-error-handler))
        (if (= o.mode :play)
            (run o)
            (let [(ok? err) (xpcall run debug.traceback o)]
              (when (not ok?) (fail! (tostring err))))))
    (nil err) (do (set love.errorhandler headless-error-handler)
                  (fail! (.. err "\n" cli.usage)))))

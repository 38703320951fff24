;; The LÖVE app: parses the command line, then either plays a scene interactively or
;; runs one command-line mode (render, print-shader, bench) and exits.

(local cli (require :src.app.cli))
(local runtime-dir (require :src.util.runtime-dir))

;; conf.lua loads this file before LÖVE starts its window (SDL's video): a headless
;; run gets a private XDG_RUNTIME_DIR until then, so that Wayland's library does not
;; print "error: XDG_RUNTIME_DIR is invalid or not set" (src/util/runtime-dir.fnl).
(local runtime-path (runtime-dir.ensure!))

(fn fail! [message]
  (io.stderr:write (.. "error: " message "\n"))
  (love.event.quit 1))

(fn print-shader [o]
  (let [frame (require :src.backend.frame)
        codegen (require :src.render.codegen)
        (scene err) (frame.load-scene o.scene)]
    (if (not scene) (fail! err)
        (let [(plan perr) (frame.plan-for scene ((. (require :src.app.bench) :plan-options) o))]
          (if (not plan) (fail! perr)
              (case (codegen.shader plan (or o.target :love))
                text (do (io.write text) (love.event.quit 0))
                (nil cerr) (fail! cerr)))))))

(fn out-options [o]
  ;; The command line's output: named as --out, never the scene file.
  {:protect [o.scene] :label (.. "--out " o.out)})

(fn render [o]
  (case ((. (require :src.app.render) :run) o)
    true (love.event.quit 0)
    (_ err) (fail! err)))

(fn probe [o]
  ;; Read and answered a batch at a time (src/app/probe.fnl): an endless stream
  ;; runs in constant memory, and each batch's lines are out before the next is read.
  (let [frame (require :src.backend.frame)
        probe-mod (require :src.app.probe)
        (scene err) (frame.load-scene o.scene)
        (plan perr) (if scene (frame.plan-for scene {:view :glow :probe? true})
                        (values nil err))
        (evaluate eerr) (if (not plan) (values nil perr)
                            o.gpu? ((. (require :src.backend.probe) :gpu-evaluator) scene plan)
                            (probe-mod.cpu-evaluator scene plan))]
    (if (not evaluate) (fail! eerr)
        (let [next-batch (probe-mod.point-reader io.stdin "stdin")]
          (var (done? failure) false)
          (while (not done?)
            ;; SIGINT and SIGTERM reach LÖVE as a quit event: with input always
            ;; arriving, the loop would never see it otherwise.
            (when ((. (require :src.app.stop) :asked?)) (set done? true))
            (let [(points rerr) (if done? (values nil "--probe: stopped (SIGINT or SIGTERM)") (next-batch))
                  (vals verr) (if points (evaluate points) (values nil rerr))]
              (if vals
                  (do (each [_ v (ipairs vals)] (io.write (probe-mod.format-line v) "\n"))
                      (io.stdout:flush))
                  (set (done? failure) (values true verr)))))
          (if failure (fail! failure) (love.event.quit 0))))))

(fn tree [o]
  (let [frame (require :src.backend.frame)
        lower (require :src.sdf.lower)
        (scene err) (frame.load-scene o.scene)]
    (if (not scene) (fail! err)
        (case (frame.plan-for scene)
          (nil perr) (fail! perr)
          plan (do (each [_ l (ipairs (lower.describe plan.tape))] (io.write l "\n"))
                   (love.event.quit 0))))))

(fn export-shader [o]
  (let [frame (require :src.backend.frame)
        export (require :src.render.export)
        output (require :src.util.output)
        (checked cerr) (output.check o.out (out-options o))
        (scene err) (if checked (frame.load-scene o.scene) (values nil cerr))
        (plan perr) (if scene (frame.plan-for scene {:fold? true}) (values nil err))
        (text xerr) (if plan (export.shadertoy scene plan) (values nil perr))]
    (if (not text) (fail! xerr)
        (case (output.write! o.out text (out-options o))
          true (do (print (.. "wrote " o.out " (Shadertoy: paste it into a new shader's Image tab)"))
                   (love.event.quit 0))
          (nil ferr) (fail! ferr)))))

(fn record [o]
  (case ((. (require :src.app.record) :run) o)
    true (love.event.quit 0)
    (_ err) (fail! err)))

(fn mesh [o]
  (case ((. (require :src.app.mesh) :run) o)
    true (love.event.quit 0)
    (_ err) (fail! err)))

(fn help []
  (io.write cli.usage "\n")
  (love.event.quit 0))

(fn help-dev []
  (io.write cli.dev-usage "\n")
  (love.event.quit 0))

(fn kinds []
  (each [_ l (ipairs ((. (require :src.sdf.card) :lines)))] (io.write l "\n"))
  (love.event.quit 0))

(fn bench [o]
  (let [bench-mod (require :src.app.bench)]
    (case (bench-mod.run-scene o)
      true (love.event.quit 0)
      (_ err) (fail! err))))

(fn bench-report [o]
  ;; The benchmark lives with the tests (test/bench/): a checkout has it, the .love
  ;; archive of `make dist` does not.
  (if (not (love.filesystem.getInfo "test/bench/report.fnl"))
      (fail! "--bench-report needs test/bench/ (a checkout of the project, not the .love archive)")
      (case ((. (require :test.bench.report) :report) o)
        true (love.event.quit 0)
        (_ err) (fail! err))))

(fn soak [o]
  (let [soak-mod (require :src.app.soak)]
    (case (soak-mod.run o)
      true (love.event.quit 0)
      (_ err) (fail! err))))

(fn edit-latency [o]
  ((. (require :src.app.edit-latency) :run) o))

(fn input-check [o]
  ((. (require :src.app.input-check) :run) o))

(fn play [o]
  (let [play-mod (require :src.app.play)]
    ;; A changed shader is compiled by a helper process first (src/app/warm.fnl),
    ;; except for a screenshot run (it waits for nothing) or with --sync-compile.
    (set o.warm? (not (or o.shot o.sync-compile?)))
    (play-mod.start! o)))

(local modes {:print-shader print-shader :render render :bench bench
              :probe probe :tree tree :kinds kinds :help help :help-dev help-dev
              :export-shader export-shader
              :record record :mesh mesh :edit-latency edit-latency
              :bench-report bench-report :soak soak :input-check input-check :play play})

(fn headless-error-handler [message]
  ;; Outside play mode nobody looks at LÖVE's error screen, and in a script or CI it
  ;; would wait forever: print the error and exit non-zero instead.
  (io.stderr:write (.. "error: " (debug.traceback (tostring message) 2) "\n"))
  (os.exit 1))

(fn love.load [args]
  ;; SDL's video has started (or never will): the stand-in folder goes.
  (runtime-dir.release! runtime-path)
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
                  (fail! (.. err "\n(love . --help lists the modes and options)")))))

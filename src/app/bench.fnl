;; Frame-time benchmarks in LÖVE: one scene (`--bench`), and the timing that the report
;; behind `make bench` (test/bench/report.fnl) is built on: variants, each a compiled
;; shader, its uniforms and a canvas, timed interleaved in rounds.

;; `pairs` under another name: a loop over `pairs` by that name is LuaJIT's ITERN,
;; which Debian 12's LuaJIT ends early once despecialised (see src/util/wire.fnl).
(local each-pair pairs)

(local status (require :src.util.status))
(local frame (require :src.backend.frame))
(local gpu (require :src.backend.gpu))
(local camera (require :src.render.camera))
(local uniforms (require :src.render.uniforms))

(local {: median} (require :src.util.stats))

(fn time-frame! [variant]
  "Draw one frame of `variant` into its canvas and wait for the GPU; milliseconds."
  (let [canvas variant.canvas
        (w h) (canvas:getDimensions)
        start (love.timer.getTime)]
    (love.graphics.push :all)
    (love.graphics.setCanvas canvas)
    (if variant.draw
        (variant.draw w h)
        (gpu.draw! variant.shader variant.uniforms w h))
    (love.graphics.pop)
    (gpu.finish! canvas)
    (* 1000 (- (love.timer.getTime) start))))

(fn make-variant [{: label : scene-path : scene-source : size : plan-options : source-path : render
                   : target}]
  "A benchmark variant: a compiled shader, its uniforms and a canvas, or nil and a
message. The scene is the file `scene-path`, or the text `scene-source`; `render`
overrides some of its render settings; `target` names codegen's target (default LÖVE's,
through gpu.compile-plan)."
  (case (if scene-source
            ((. (require :src.scene.load) :load-string) scene-source label)
            (frame.load-scene scene-path))
    (nil err) (values nil err)
    scene (case (do (each [k v (each-pair (or render {}))] (tset scene.render k v))
                    (frame.plan-for scene plan-options))
            (nil err) (values nil err)
            plan (let [[w h] size
                       source (if source-path (love.filesystem.read source-path)
                                  target ((. (require :src.render.codegen) :shader) plan target))]
                   (case (let [start (love.timer.getTime)
                               (shader err) (if source (gpu.compile-source source label)
                                                (gpu.compile-plan plan label))]
                           (values shader err (* 1000 (- (love.timer.getTime) start))))
                     (nil err) (values nil err)
                     (shader _ compile-ms) {: label : shader : plan : compile-ms
                             :uniforms (uniforms.pack scene plan (camera.from-scene scene) w h)
                             :canvas (love.graphics.newCanvas w h)
                             :times []})))))

(fn run-rounds! [variants rounds]
  ;; One untimed round first: the driver finishes compiling on first use.
  (each [_ v (ipairs variants)] (set v.first-ms (time-frame! v)))
  (for [round 1 rounds]
    (each [_ v (ipairs variants)]
      (table.insert v.times (time-frame! v)))
    (status.update! (string.format "round %d/%d" round rounds)))
  (status.done!)
  (each [_ v (ipairs variants)] (set v.median (median v.times))))

(fn plan-options [o]
  "The plan options of `love . --bench` and `--print-shader` for command-line options
`o`: its view; with --interpret, the tape interpreter holding every kind
(interpret.catalogue), as the player's."
  {:view o.view :interpret? o.interpret?
   :instructions (when o.interpret? ((. (require :src.sdf.interpret) :catalogue)))})

(fn run-scene [o]
  "`love . --bench SCENE`: median milliseconds per frame of one scene."
  (let [size (or o.size [1920 1080])]
    (case (make-variant {:label o.scene :scene-path o.scene :size size
                         :plan-options (plan-options o)})
      (nil err) (values nil err)
      v (let [(_ version _ device) (love.graphics.getRendererInfo)]
          (print (.. "renderer: " device " (OpenGL " version ")"))
          (run-rounds! [v] o.frames)
          (print (string.format "%s %dx%d: median %.1f ms per frame over %d frames"
                                o.scene (. size 1) (. size 2) v.median o.frames))
          ;; llvmpipe finishes compiling on first use: the first frame's excess over
          ;; the median is that part of the compile.
          (print (string.format "shader: newShader %.0f ms, first frame %.0f ms (%.0f ms over the median); uniforms %s"
                                v.compile-ms v.first-ms (- v.first-ms v.median)
                                (if v.plan.load-once? "read once per pixel" "read where used")))
          true))))

{: make-variant : run-rounds! : run-scene : plan-options}

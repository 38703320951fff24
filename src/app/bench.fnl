;; Frame-time benchmarks in LÖVE: one scene (`--bench`), and the report behind
;; `make bench`, which times several shader variants interleaved in one run so that the
;; ratios it prints are not skewed by a shared, noisy machine.

(local frame (require :src.backend.frame))
(local gpu (require :src.backend.gpu))
(local camera (require :src.render.camera))
(local uniforms (require :src.render.uniforms))

;; The article's own CPU program, measured on this machine at 256x224 for the seed scene.
(local article-ms-256x224 2900)

(local median (. (require :src.verify.compare) :median))

(fn time-frame! [variant]
  "Draw one frame of `variant` into its canvas and wait for the GPU; milliseconds."
  (let [canvas variant.canvas
        (w h) (canvas:getDimensions)
        start (love.timer.getTime)]
    (love.graphics.push :all)
    (love.graphics.setCanvas canvas)
    (gpu.draw! variant.shader variant.uniforms w h)
    (love.graphics.pop)
    (gpu.finish! canvas)
    (* 1000 (- (love.timer.getTime) start))))

(fn make-variant [{: label : scene-path : size : plan-options : source-path}]
  "A benchmark variant: a compiled shader, its uniforms and a canvas, or nil and a message."
  (case (frame.load-scene scene-path)
    (nil err) (values nil err)
    scene (case (frame.plan-for scene plan-options)
            (nil err) (values nil err)
            plan (let [[w h] size
                       source (if source-path
                                  (love.filesystem.read source-path)
                                  ((. (require :src.render.codegen) :shader) plan :love))]
                   (case (let [start (love.timer.getTime)
                               (shader err) (gpu.compile-source source label)]
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
    (io.stderr:write (string.format "\rround %d/%d" round rounds))
    (io.stderr:flush))
  (io.stderr:write "\n")
  (each [_ v (ipairs variants)] (set v.median (median v.times))))

(fn run-scene [o]
  "`love . --bench SCENE`: median milliseconds per frame of one scene."
  (let [size (or o.size [1920 1080])]
    (case (make-variant {:label o.scene :scene-path o.scene :size size
                         :plan-options {:view o.view}})
      (nil err) (values nil err)
      v (do (run-rounds! [v] o.frames)
            (print (string.format "%s %dx%d: median %.1f ms per frame over %d frames"
                                  o.scene (. size 1) (. size 2) v.median o.frames))
            ;; llvmpipe finishes compiling on first use: the first frame's excess over
            ;; the median is that part of the compile.
            (print (string.format "shader: newShader %.0f ms, first frame %.0f ms (%.0f ms over the median)"
                                  v.compile-ms v.first-ms (- v.first-ms v.median)))
            true))))

(fn report [o]
  "`make bench`: generated vs hand-written shader, specialized vs all-features shader,
and our frame times next to the article's CPU program."
  (let [hd [1920 1080]
        small [256 224]
        specs [{:label "seed, generated, 1920x1080" :scene-path "scenes/seed.fnl" :size hd}
               {:label "seed, hand-written, 1920x1080" :scene-path "scenes/seed.fnl" :size hd
                :source-path "test/bench/seed-handwritten.glsl"}
               {:label "spheres, specialized, 1920x1080" :scene-path "scenes/spheres.fnl" :size hd}
               {:label "spheres, all features, 1920x1080" :scene-path "scenes/spheres.fnl" :size hd
                :plan-options {:uber? true}}
               {:label "seed, generated, 256x224" :scene-path "scenes/seed.fnl" :size small}]
        variants []]
    (var err nil)
    (each [_ spec (ipairs specs) &until err]
      (case (make-variant spec)
        (nil e) (set err e)
        v (table.insert variants v)))
    (if err
        (values nil err)
        (let [[gen hand spec uber small-gen] variants
              (_ version _ device) (love.graphics.getRendererInfo)]
          (print (.. "renderer: " device " (OpenGL " version ")"))
          (print (.. "frames per variant: " o.frames ", interleaved, after one warm-up round"))
          (run-rounds! variants o.frames)
          (each [_ v (ipairs variants)]
            (print (string.format "%-36s median %8.1f ms" v.label v.median)))
          (print (string.format "generated / hand-written (seed, 1920x1080): %.3f (goal <= 1.05)"
                                (/ gen.median hand.median)))
          (print (string.format "specialized / all features (spheres, 1920x1080): %.3f"
                                (/ spec.median uber.median)))
          (print (string.format "article's CPU program, seed 256x224: %d ms; ours %.1f ms (%.0fx faster)"
                                article-ms-256x224 small-gen.median
                                (/ article-ms-256x224 small-gen.median)))
          (print (string.format "pixel rate at 1920x1080 vs the article's at 256x224: %.0fx"
                                (/ (/ (* 1920 1080) gen.median)
                                   (/ (* 256 224) article-ms-256x224))))
          true))))

{: run-scene : report}

;; The player's compile helper (see warm.fnl). It compiles a shader and draws it once
;; into a small canvas, so the driver's on-disk cache holds the program and the code
;; of its first draw. conf.lua loads this module instead of main.fnl when the command
;; line asks for it, so the helper starts in about a quarter of a second (the player's
;; modules take a second to compile).
;;
;;   love GAME --warm-shader FILE.glsl   one shader; exits 0, or 1 with the message
;;   love GAME --warm-server DIR PID     the player's helper: jobs from DIR (job-N.glsl,
;;                                       answered by job-N.done) until PID is gone

(local quad (require :src.backend.quad))
(local {: job-path : write-whole! : remove-jobs!} (require :src.app.warm))

(fn arg-after [args flag ?k]
  "The argument `?k` places (default 1) after `flag` in `args`."
  (var found nil)
  (each [i a (ipairs args)]
    (when (= a flag) (set found (. args (+ i (or ?k 1))))))
  found)

(fn textures [source]
  "The textures the player will bind, from the lines `//warm-texture NAME W H` it puts
before the shader: [[name w h] ...]."
  (icollect [name w h (source:gmatch "//warm%-texture ([%w_]+) (%d+) (%d+)\n")]
    [name (tonumber w) (tonumber h)]))

(fn shader-text [source]
  ;; Without those lines: the text the player compiles, so that the driver's cache
  ;; finds it.
  (pick-values 1 (source:gsub "//warm%-texture [^\n]*\n" "")))

(fn read-file [path]
  (case (io.open path :rb)
    f (let [t (f:read :*a)] (f:close) t)))

(fn warm-source! [source]
  "Compile `source` and draw it once. True, or nil and the driver's message."
  (case (pcall love.graphics.newShader (shader-text source))
    (false err) (values nil (.. "the shader did not compile:\n" (tostring err)))
    (true shader)
    (let [canvas (love.graphics.newCanvas 8 8)
          ;; A field's textures as the player makes them: rgba32f, sampled nearest,
          ;; of the same size (gpu.float-image). The driver's code for the shader
          ;; depends on the format, the sampler and whether each side is a power of two.
          images (icollect [_ [name w h] (ipairs (textures source))]
                   (when (shader:hasUniform name)
                     (let [data (love.image.newImageData w h :rgba32f)
                           image (love.graphics.newImage data)]
                       (data:release)
                       (image:setFilter :nearest :nearest)
                       (shader:send name image)
                       image)))]
      (quad.draw-into! canvas shader)
      ;; Reading a pixel back waits until the draw has run.
      (: (canvas:newImageData 1 1 0 0 1 1) :release)
      (each [_ image (ipairs images)] (image:release))
      (canvas:release)
      (shader:release)
      true)))

(fn alive? [pid]
  (case (io.open (.. "/proc/" pid "/stat") :rb)
    f (do (f:close) true)
    _ false))

(fn serve! [dir pid]
  "Take jobs from `dir` in order until process `pid` is gone, then remove `dir`. Its
own process id is in `dir`/pid."
  (case (io.popen "echo $PPID")
    p (let [own (p:read "*l")] (p:close) (write-whole! (.. dir "/pid") own)))
  (var n 1)
  (while (alive? pid)
    (let [job (job-path dir n :glsl)]
      (case (read-file job)
        source (do (os.remove job)
                   (write-whole! (job-path dir n :done) (if (warm-source! source) "ok" "failed"))
                   (set n (+ n 1)))
        _ (love.timer.sleep 0.02))))
  ;; What the player left behind: answers it never read, a job it never saw taken.
  (remove-jobs! dir (math.max 1 (- n 1)) (+ n 1))
  (os.remove (.. dir "/pid"))
  (os.remove dir)
  (love.event.quit 0))

(fn fail! [message]
  (io.stderr:write (.. "error: " message "\n"))
  (love.event.quit 1))

(fn run! [args]
  "love.load of the helper: --warm-server DIR PID, or --warm-shader FILE."
  (let [dir (arg-after args "--warm-server")
        pid (tonumber (arg-after args "--warm-server" 2))
        path (arg-after args "--warm-shader")
        source (and path (read-file path))]
    (if (and dir pid) (serve! dir pid)
        (not source) (fail! (.. (tostring path) ": cannot read the shader"))
        (case (warm-source! source)
          true (love.event.quit 0)
          (_ err) (fail! (.. path ": " err))))))

(fn install! []
  "Make LÖVE run the helper: conf.lua calls this instead of loading main.fnl."
  (set love.errorhandler
       (fn [message]
         (io.stderr:write (.. "error: " (tostring message) "\n"))
         (os.exit 1)))
  (set love.load run!))

{: install! : run! : arg-after : textures : shader-text}

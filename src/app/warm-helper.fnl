;; The player's compile helper (see warm.fnl). It compiles a shader and draws it once
;; into a small canvas, so the driver's on-disk cache holds the program and the code
;; of its first draw. conf.lua loads this module instead of main.fnl when the command
;; line asks for it, so the helper starts in about a quarter of a second (the player's
;; modules take a second to compile).
;;
;;   love GAME --warm-shader FILE.glsl   one shader; exits 0, or 1 with the message
;;   love GAME --warm-server DIR PID     the player's helper: jobs from DIR (job-N.glsl,
;;                                       answered by job-N.done) until PID is gone or
;;                                       DIR/quit appears

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

(fn same-kind [n]
  "The smallest side that is a power of two when `n` is one, and not when it is not."
  (if (= n (^ 2 (math.floor (+ 0.5 (/ (math.log n) (math.log 2)))))) 1 3))

(fn read-file [path]
  (case (io.open path :rb)
    f (let [t (f:read :*a)] (f:close) t)))

(fn warm-source! [source]
  "Compile `source` and draw it once. True, or nil and the driver's message."
  (case (pcall love.graphics.newShader (shader-text source))
    (false err) (values nil (.. "the shader did not compile:\n" (tostring err)))
    (true shader)
    (let [canvas (love.graphics.newCanvas 8 8)
          ;; A field's textures as the player makes them: rgba32f, sampled nearest
          ;; (gpu.float-image), each side a power of two where the player's is. The
          ;; driver's code for the shader depends on the format, the sampler and
          ;; whether each side is a power of two (llvmpipe's key holds those flags,
          ;; not the sizes), so each side is 1 or 3: at their own sizes, 1,000,000
          ;; spheres' textures took the helper to 510 MB.
          images (icollect [_ [name w h] (ipairs (textures source))]
                   (when (shader:hasUniform name)
                     (let [data (love.image.newImageData (same-kind w) (same-kind h) :rgba32f)
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

(fn task-stat [pid tid]
  ;; A thread's state letter and CPU ticks so far (utime + stime), from its stat line
  ;; (the fields after its name, which may hold spaces and parentheses).
  (case (io.open (.. "/proc/" pid "/task/" tid "/stat") :rb)
    f (let [line (or (f:read "*l") "")
            _ (f:close)
            rest (line:match ".*%) (.*)$")
            fields (icollect [w (string.gmatch (or rest "") "%S+")] w)]
        (when (. fields 13)
          (values (. fields 1) (+ (tonumber (. fields 12)) (tonumber (. fields 13))))))))

(fn cache-writers [pid]
  "The threads of process `pid` that write Mesa's on-disk shader cache (named disk$N)."
  (case (io.popen (.. "grep -l 'disk[$]' /proc/" pid "/task/*/comm 2>/dev/null"))
    p (let [out (p:read :*a)]
        (p:close)
        (icollect [tid (out:gmatch "/task/(%d+)/comm")] tid))))

(fn writers-idle? [pid tids before]
  "True when every cache writer in `tids` sleeps and has used no CPU since `before`
(tid -> ticks, updated): Mesa's writer sleeps only with its queue empty."
  (accumulate [idle? true _ tid (ipairs tids)]
    (let [(st ticks) (task-stat pid tid)
          same? (= ticks (. before tid))]
      (tset before tid ticks)
      (and idle? (or (= st nil) (and (= st "S") same?))))))

(fn wait-for-cache-writes! [pid]
  "Return once Mesa has written what this process compiled to its on-disk cache. Mesa
writes in a thread of its own at the lowest priority (SCHED_BATCH, nice 19): on a
busy machine the last entry of a shader (its llvmpipe code, put at the first draw)
landed 0.1-0.5 s after the helper answered, and a player that compiled meanwhile
missed it and compiled the shader again, freezing its window. Waits until each
writer thread has slept, its CPU time unchanged, over three looks 5 ms apart; a
driver without such threads (NVIDIA) returns at once. 30 s at most (a hang guard)."
  (let [tids (or (cache-writers pid) [])
        before {}
        stop (+ (love.timer.getTime) 30)]
    (var calm 0)
    (while (and (> (length tids) 0) (< calm 3) (< (love.timer.getTime) stop))
      (set calm (if (writers-idle? pid tids before) (+ calm 1) 0))
      (love.timer.sleep 0.005))))

(fn alive? [pid]
  (case (io.open (.. "/proc/" pid "/stat") :rb)
    f (do (f:close) true)
    _ false))

(fn serve! [dir pid]
  "Take jobs from `dir` in order until process `pid` is gone, then remove `dir`. Its
own process id is in `dir`/pid."
  (local own (case (io.popen "echo $PPID")
               p (let [own (p:read "*l")] (p:close) own)))
  (write-whole! (.. dir "/pid") own)
  (var n 1)
  ;; The player asks it to quit (quit) before it has taken a job; once it has, it is
  ;; killed instead (warm.stop-server!).
  (while (and (alive? pid) (not (read-file (.. dir "/quit"))))
    (let [job (job-path dir n :glsl)]
      (case (read-file job)
        source (do (os.remove job)
                   (let [ok? (warm-source! source)]
                     (when own (wait-for-cache-writes! own))
                     (write-whole! (job-path dir n :done) (if ok? "ok" "failed")))
                   (set n (+ n 1)))
        _ (love.timer.sleep 0.02))))
  ;; What the player left behind: answers it never read, a job it never saw taken.
  (remove-jobs! dir (math.max 1 (- n 1)) (+ n 1))
  (os.remove (.. dir "/pid"))
  (os.remove (.. dir "/quit"))
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
          true (do (case (io.popen "echo $PPID")
                     p (let [own (p:read "*l")] (p:close) (wait-for-cache-writes! own)))
                   (love.event.quit 0))
          (_ err) (fail! (.. path ": " err))))))

(fn install! []
  "Make LÖVE run the helper: conf.lua calls this instead of loading main.fnl."
  (set love.errorhandler
       (fn [message]
         (io.stderr:write (.. "error: " (tostring message) "\n"))
         (os.exit 1)))
  (set love.load run!))

{: install! : run! : arg-after : textures : shader-text : cache-writers : writers-idle?
 : wait-for-cache-writes!}

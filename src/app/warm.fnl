;; Structural edits without a frozen window. Compiling a new scene's shader blocks the
;; process that asks for it: on llvmpipe a showcase tree takes 0.6 to 2.3 s, most of
;; it in LLVM, and no driver here compiles in the background. Mesa and NVIDIA keep
;; what they compile in an on-disk cache that every process shares, so the player
;; hands the new shader to a helper process (`love GAME --warm-shader FILE`: compile,
;; draw once, quit) and keeps drawing the last scene meanwhile; once the helper is
;; done the player's own compile finds the cache filled and takes tens of ms.
;; A helper that fails, or a driver with no cache, leaves the compile to the player as
;; before: warming only ever moves work off the player's thread.

(local max-settled 64)
(local max-failures 3)

;; The helper runs in a LÖVE thread (os.execute blocks it, not the player) and reports
;; whether it succeeded on the channel it was given.
(local thread-code "
local command, channel = ...
local status = os.execute(command)
channel:push(status == 0 or status == true)
")

(fn shell-quote [s]
  (.. "'" (pick-values 1 (s:gsub "'" "'\\''")) "'"))

(fn helper-command [love-exe game-source shader-path]
  "The shell command that fills the driver's cache with the shader in `shader-path`:
LÖVE on the same game, headless (SDL's offscreen driver; Mesa shares one cache between
it and a window), its output discarded."
  (string.format "SDL_VIDEODRIVER=offscreen %s %s --warm-shader %s >/dev/null 2>&1"
                 (shell-quote love-exe) (shell-quote game-source) (shell-quote shader-path)))

(fn env-true? [v]
  (and v (not= nil (. {:1 true :true true :y true :yes true} (v:lower)))))

(fn cache-shared? [getenv version vendor]
  "Whether the driver keeps compiled shaders on disk where another process finds them:
Mesa (its `version` string names it) unless MESA_SHADER_CACHE_DISABLE (or the older
MESA_GLSL_CACHE_DISABLE) is set, and NVIDIA (`vendor`) unless __GL_SHADER_DISK_CACHE
is 0. `getenv` looks up the environment (os.getenv)."
  (if (string.find (or version "") "Mesa" 1 true)
      (not (or (env-true? (getenv "MESA_SHADER_CACHE_DISABLE"))
               (env-true? (getenv "MESA_GLSL_CACHE_DISABLE"))))
      (string.find (or vendor "") "NVIDIA" 1 true)
      (not= (getenv "__GL_SHADER_DISK_CACHE") "0")
      false))

(fn love-executable []
  ;; The running LÖVE binary (Linux: /proc), else the name it was started by.
  (let [p (io.popen "readlink /proc/$PPID/exe 2>/dev/null")
        exe (when p (let [l (p:read "*l")] (p:close) l))]
    (if (and exe (not= exe "")) exe (?. _G.arg -2))))

(fn new []
  "A warmer for the running player: enabled on Linux when the driver's cache is shared
(see cache-shared?) and the LÖVE binary and game folder are known."
  (let [(_ version vendor) (love.graphics.getRendererInfo)
        exe (when (= (love.system.getOS) "Linux") (love-executable))
        source (love.filesystem.getSource)]
    {:enabled? (and exe source (cache-shared? os.getenv version vendor) true)
     :exe exe :source source
     ;; plan key -> :done or :failed, once a helper has finished for it
     :settled {} :settled-count 0
     ;; the helper at work ({: key : thread : channel : path}) and the one key waiting
     ;; for it (a newer request replaces an older waiting one)
     :running nil :queued nil
     ;; how a helper is started (warm_spec gives a stand-in; nil: a LÖVE thread)
     :start! nil}))

(fn start! [w key source]
  (let [path (os.tmpname)
        out (io.open path :w)]
    (if (not out)
        (values nil (.. path ": cannot write the shader for the helper"))
        (let [channel (love.thread.newChannel)
              thread (love.thread.newThread thread-code)]
          (out:write source)
          (out:close)
          (thread:start (helper-command w.exe w.source path) channel)
          (set w.running {: key : thread : channel : path})
          true))))

(fn settle! [w key outcome]
  (when (>= w.settled-count max-settled)
    (set w.settled {})
    (set w.settled-count 0))
  (tset w.settled key outcome)
  (set w.settled-count (+ w.settled-count 1)))

(fn poll! [w]
  "Collect a finished helper and start the waiting one. Call once a frame."
  (let [job w.running]
    (when job
      (let [ok (job.channel:pop)
            err (job.thread:getError)]
        (when (or (not= ok nil) err)
          (os.remove job.path)
          (settle! w job.key (if (and ok (not err)) :done :failed))
          (set w.running nil)
          ;; A helper that fails again and again (no LÖVE to start, a driver that
          ;; will not start headless) only adds its start to every edit: stop asking.
          (set w.failures (if (and ok (not err)) 0 (+ (or w.failures 0) 1)))
          (when (>= w.failures max-failures)
            (set w.enabled? false)
            (set w.gave-up? true))))))
  (when (and (not w.running) w.queued)
    (let [{: key : source} w.queued]
      (set w.queued nil)
      (when (not (. w.settled key))
        (when (not ((or w.start! start!) w key source))
          (settle! w key :failed))))))

(fn status [w key]
  "What became of `key`: :done or :failed once its helper finished, :running or
:queued meanwhile, nil when it was never asked for."
  (or (. w.settled key)
      (when (= (?. w.running :key) key) :running)
      (when (= (?. w.queued :key) key) :queued)))

(fn settled? [w key]
  "True once a helper has finished with `key` (done or failed)."
  (not= nil (. w.settled key)))

(fn ready? [w key source-fn]
  "True when the player may compile the shader of plan `key` now: its helper has
finished (or warming is off). Otherwise asks for a helper (queued behind the one at
work; `(source-fn)` gives the shader's text, or nil and a message: then the player
compiles it and shows the message) and returns false."
  (if (not w.enabled?) true
      (settled? w key) true
      (status w key) false
      (case (source-fn)
        source (do (set w.queued {: key : source})
                   (poll! w)
                   false)
        _ (do (settle! w key :failed) true))))

{: new : ready? : settled? : poll! : status : helper-command : cache-shared? : shell-quote}

;; Structural edits without a frozen window. Compiling a new scene's shader blocks the
;; process that asks for it: on llvmpipe a showcase tree takes 0.6 to 2.3 s, most of
;; it in LLVM, and no driver here compiles in the background. Mesa and NVIDIA keep
;; what they compile in an on-disk cache that every process shares, so the player
;; hands the new shader to a helper process (src/app/warm-helper.fnl: it compiles the
;; shader and draws it once) and keeps drawing the last scene meanwhile; once the
;; helper is done the player's own compile finds the cache filled and takes tens of ms.
;; A helper that fails, or a driver with no cache, leaves the compile to the player as
;; before: warming only ever moves work off the player's thread.
;;
;; The helper is one process for the player's lifetime (`love GAME --warm-server DIR
;; PID`, started with the first request), so an edit does not pay LÖVE's start (about
;; 0.3 s). It takes jobs as files in DIR: the player writes job-N.glsl, the helper
;; answers job-N.done ("ok" or "failed"); both appear whole (written, then renamed). It
;; quits when process PID (the player) is gone. A LÖVE thread waits on it (os.execute),
;; so the player knows when it has died: its job fails, and the next request starts a
;; new one.

(local max-settled 64)
(local max-failures 3)

;; The helper runs under a LÖVE thread (os.execute blocks it, not the player), which
;; says on its channel when the helper has quit.
(local thread-code "
local command, channel = ...
local status = os.execute(command)
channel:push(status == 0 or status == true)
")

(fn shell-quote [s]
  (.. "'" (pick-values 1 (s:gsub "'" "'\\''")) "'"))

(fn helper-command [love-exe game-source dir pid]
  "The shell command that starts the helper: LÖVE on the same game, headless (SDL's
offscreen driver; Mesa shares one cache between it and a window), taking jobs in
`dir` for as long as process `pid` lives, its output discarded."
  (string.format "SDL_VIDEODRIVER=offscreen %s %s --warm-server %s %d >/dev/null 2>&1"
                 (shell-quote love-exe) (shell-quote game-source) (shell-quote dir) pid))

(fn job-path [dir n ext]
  "The file of job `n` in `dir`: job-N.glsl (the shader) or job-N.done (the answer)."
  (.. dir "/job-" n "." ext))

(fn remove-jobs! [dir first final]
  "Remove the files of jobs `first` to `final` in `dir`, whatever stage they are in."
  (for [i first final]
    (each [_ ext (ipairs [:glsl :done :glsl.part :done.part])]
      (os.remove (job-path dir i ext)))))

(fn write-whole! [path text]
  "Write `text` to `path` so that a reader never sees part of it (a temporary file
renamed over it). True, or nil and a message."
  (let [tmp (.. path ".part")]
    (case (io.open tmp :wb)
      f (do (f:write text) (f:close)
            (case (os.rename tmp path)
              true true
              (_ err) (values nil err)))
      (nil err) (values nil err))))

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

(fn shell-line [command]
  (let [p (io.popen command)
        l (when p (p:read "*l"))]
    (when p (p:close))
    (when (and l (not= l "")) l)))

(fn love-executable []
  ;; The running LÖVE binary (Linux: /proc), else the name it was started by.
  (or (shell-line "readlink /proc/$PPID/exe 2>/dev/null") (?. _G.arg -2)))

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
     ;; helpers that failed in a row (see poll!)
     :failures 0
     ;; the job at work ({: key :check (fn [] nil | :done | :failed)}) and the one
     ;; key waiting for it (a newer request replaces an older waiting one)
     :running nil :queued nil
     ;; the helper process ({: dir : thread : channel : jobs}, jobs: the last job's
     ;; number)
     :server nil
     ;; how a job is started (warm_spec gives a stand-in; nil: start!)
     :start! nil}))

(fn start-server! [w]
  ;; The helper process and its job folder (a fresh name from os.tmpname).
  (let [base (os.tmpname)
        dir (.. base ".warm")
        pid (tonumber (shell-line "echo $PPID"))]
    (os.remove base)
    (if (not (and pid (case (os.execute (.. "mkdir -m 700 " (shell-quote dir)))
                        0 true
                        true true
                        _ false)))
        (values nil (.. dir ": cannot make the helper's folder"))
        (let [channel (love.thread.newChannel)
              thread (love.thread.newThread thread-code)]
          (thread:start (helper-command w.exe w.source dir pid) channel)
          (set w.server {: dir : thread : channel :jobs 0})
          w.server))))

(fn prepare! [w]
  "Start the helper now, before the first edit needs it (it takes about 0.3 s to start)."
  (when (and w.enabled? (not w.server))
    (start-server! w)))

(fn server-gone? [server]
  (or (not= nil (server.channel:peek)) (not= nil (server.thread:getError))))

(fn forget-server! [w]
  ;; A helper that died (it removes its folder when it quits on its own): what it
  ;; left in its folder, and the folder.
  (let [server w.server]
    (set w.server nil)
    (remove-jobs! server.dir 1 (+ server.jobs 1))
    (os.remove (.. server.dir "/pid"))
    (os.remove server.dir)))

(fn start! [w key source]
  "Give the helper the job of compiling `source` for plan `key` (starting the helper
first when there is none). True, or nil and a message."
  (when (and w.server (server-gone? w.server))
    (forget-server! w))
  (case (or w.server (start-server! w))
    server (let [n (+ server.jobs 1)
                 done (job-path server.dir n :done)]
             (set server.jobs n)
             (case (write-whole! (job-path server.dir n :glsl) source)
               true (do (set w.running
                             {: key
                              :check #(case (io.open done :rb)
                                        f (let [answer (f:read :*a)]
                                            (f:close)
                                            (os.remove done)
                                            (if (= answer "ok") :done :failed))
                                        _ (when (server-gone? server)
                                            (when (= w.server server) (forget-server! w))
                                            :failed))})
                        true)
               (_ err) (values nil err)))
    (nil err) (values nil err)))

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
      (case (job.check)
        outcome (do (settle! w job.key outcome)
                    (set w.running nil)
                    ;; A helper that fails again and again (no LÖVE to start, a driver
                    ;; that will not start headless) only delays every edit: stop asking.
                    (set w.failures (if (= outcome :done) 0 (+ w.failures 1)))
                    (when (>= w.failures max-failures)
                      (set w.enabled? false)
                      (set w.gave-up? true))))))
  (when (and (not w.running) w.queued)
    (let [{: key : source} w.queued]
      (set w.queued nil)
      (when (and (not (. w.settled key))
                 (not ((or w.start! start!) w key source)))
        (settle! w key :failed)))))

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

{: new : prepare! : ready? : settled? : poll! : status : helper-command : job-path : write-whole!
 : remove-jobs!
 : cache-shared? : shell-quote}

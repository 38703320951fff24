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
;; quits when process PID (the player) is gone. A LÖVE thread waits on it (waitpid),
;; so the player knows when it has died: its job fails, and the next request starts a
;; new one.
;;
;; Two helpers, two lanes (issue 42): the edit lane compiles what the player must show
;; next (a structural edit, a new view), the background lane what only improves the
;; picture on screen (the folded shader, the still's). One process compiles one shader
;; at a time, and a still's shader takes 3 to 30 s on llvmpipe: in one queue an edit
;; made meanwhile waited for it (4-19 s instead of 0.5-0.85 s). Now a new request in
;; the edit lane cancels the background lane: its waiting job is dropped and its helper,
;; at work for a state that is no longer shown, is killed (the next background request
;; starts another, off the edit's path). The background helper also runs niced, so it
;; never takes the cores from the player's frames.

(local max-settled 64)
(local max-failures 3)

;; The helper runs under a LÖVE thread (the wait blocks it, not the player), which
;; says on its channel when the helper has quit. The thread starts the shell with
;; posix_spawn and waits in waitpid: os.execute (C's system()) ignores SIGINT and
;; SIGQUIT in the whole process while its command runs, so the player could not be
;; stopped by ^C while a helper lived; and a read from io.popen holds its stream's
;; lock, which LuaJIT's next io.popen in the player waits for (it flushes every
;; stream first): the player froze.
(local thread-code "
local command, channel = ...
local ffi = require('ffi')
pcall(ffi.cdef, [[
int posix_spawnp(int *pid, const char *file, const void *file_actions,
                 const void *attrp, char *const argv[], char *const envp[]);
int waitpid(int pid, int *status, int options);
extern char **environ;
]])
local pid = ffi.new('int[1]')
local args = {'sh', '-c', command}
local argv = ffi.new('char *[4]')
local strings = {}  -- the C strings argv points at, kept alive
for i, a in ipairs(args) do
  strings[i] = ffi.new('char[?]', #a + 1, a)
  argv[i - 1] = strings[i]
end
local ok = false
if ffi.C.posix_spawnp(pid, 'sh', nil, nil, argv, ffi.C.environ) == 0 then
  local status = ffi.new('int[1]')
  local r
  repeat r = ffi.C.waitpid(pid[0], status, 0) until r ~= -1 or ffi.errno() ~= 4
  ok = r == pid[0] and status[0] == 0
end
channel:push(ok)
")

(fn shell-quote [s]
  (.. "'" (pick-values 1 (s:gsub "'" "'\\''")) "'"))

(fn helper-command [love-exe game-source dir pid ?nice]
  "The shell command that starts the helper: LÖVE on the same game, headless (SDL's
offscreen driver; Mesa shares one cache between it and a window), taking jobs in
`dir` for as long as process `pid` lives, its output discarded; at niceness `?nice`
when given (the background lane's)."
  (string.format "SDL_VIDEODRIVER=offscreen %s%s %s --warm-server %s %d >/dev/null 2>&1"
                 (if ?nice (string.format "nice -n %d " ?nice) "")
                 (shell-quote love-exe) (shell-quote game-source) (shell-quote dir) pid))

;; The background helper's niceness: the player's frames (nice 0) come first.
(local background-nice 10)

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
     ;; The edit lane (w itself): the job at work ({: key :check (fn [] nil | :done
     ;; | :failed)}) and the one key waiting for it (a newer request replaces an
     ;; older waiting one)
     :running nil :queued nil
     ;; its helper process ({: dir : thread : channel : jobs}, jobs: the last job's
     ;; number)
     :server nil
     ;; The background lane: the same fields, its own helper (niced).
     :background {:running nil :queued nil :server nil :nice background-nice}
     ;; background jobs cancelled by an edit (warm_spec and edit-latency read it)
     :cancelled 0
     ;; how a job is started (warm_spec gives a stand-in; nil: start!)
     :start! nil}))

(fn start-server! [w lane]
  ;; The helper process of `lane` and its job folder (a fresh name from os.tmpname).
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
          (thread:start (helper-command w.exe w.source dir pid lane.nice) channel)
          (set lane.server {: dir : thread : channel :jobs 0})
          lane.server))))

(fn prepare! [w]
  "Start the helper now, before the first edit needs it (it takes about 0.3 s to start)."
  (when (and w.enabled? (not w.server))
    (start-server! w w)))

(fn server-gone? [server]
  (or (not= nil (server.channel:peek)) (not= nil (server.thread:getError))))

(fn forget-server! [lane]
  ;; A helper that died (it removes its folder when it quits on its own): what it
  ;; left in its folder, and the folder.
  (let [server lane.server]
    (set lane.server nil)
    (remove-jobs! server.dir 1 (+ server.jobs 1))
    (os.remove (.. server.dir "/pid"))
    (os.remove server.dir)))

(fn start! [lane key source w]
  "Give the helper of `lane` (of warmer `w`) the job of compiling `source` for plan
`key` (starting the helper first when there is none). True, or nil and a message."
  (when (and lane.server (server-gone? lane.server))
    (forget-server! lane))
  (case (or lane.server (start-server! w lane))
    server (let [n (+ server.jobs 1)
                 done (job-path server.dir n :done)]
             (set server.jobs n)
             (case (write-whole! (job-path server.dir n :glsl) source)
               true (do (set lane.running
                             {: key
                              :check #(case (io.open done :rb)
                                        f (let [answer (f:read :*a)]
                                            (f:close)
                                            (os.remove done)
                                            (if (= answer "ok") :done :failed))
                                        _ (when (server-gone? server)
                                            (when (= lane.server server) (forget-server! lane))
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

(fn poll-lane! [w lane]
  (let [job lane.running]
    (when job
      (case (job.check)
        outcome (do (settle! w job.key outcome)
                    (set lane.running nil)
                    ;; A helper that fails again and again (no LÖVE to start, a driver
                    ;; that will not start headless) only delays every edit: stop asking.
                    (set w.failures (if (= outcome :done) 0 (+ w.failures 1)))
                    (when (>= w.failures max-failures)
                      (set w.enabled? false)
                      (set w.gave-up? true))))))
  (when (and w.enabled? (not lane.running) lane.queued)
    (let [{: key : source} lane.queued]
      (set lane.queued nil)
      (when (and (not (. w.settled key))
                 (not ((or w.start! start!) lane key source w)))
        (settle! w key :failed)))))

(fn poll! [w]
  "Collect finished helpers and start the waiting jobs. Call once a frame."
  (poll-lane! w w)
  (when w.background (poll-lane! w w.background)))

(fn helper-pid [server]
  ;; The helper's process id, from the file it writes before it takes a job.
  (case (io.open (.. server.dir "/pid") :rb)
    f (let [l (f:read "*l")] (f:close) (tonumber l))))

(fn stop-server! [lane]
  "Stop the helper of `lane` now, whatever it is doing: killed when it has said who it
is (a compile cannot be interrupted otherwise; SDL would turn SIGTERM into a quit
event it never reads, so SIGKILL), else told to quit before it takes a job (it
writes its pid first, and looks for `quit` before each job)."
  (case lane.server
    server (case (helper-pid server)
             pid (do (os.execute (.. "kill -9 " pid " 2>/dev/null"))
                     (forget-server! lane))
             ;; Not started yet: it removes its folder itself when it quits.
             _ (do (write-whole! (.. server.dir "/quit") "quit")
                   (set lane.server nil)))))

(fn cancel-background! [w]
  "Drop the background lane's waiting job and stop its job at work (see stop-server!):
an edit never waits for them. Their keys stay unsettled, so they are asked for again
if they are wanted again."
  (let [lane w.background]
    (when lane
      (when (or lane.running lane.queued)
        (set w.cancelled (+ (or w.cancelled 0) 1)))
      (set lane.queued nil)
      (when lane.running
        (set lane.running nil)
        ;; warm_spec's stand-in jobs have no process.
        (when (not w.start!) (stop-server! lane))))))

(fn status [w key]
  "What became of `key`: :done or :failed once its helper finished, :running or
:queued meanwhile (in either lane), nil when it was never asked for."
  (or (. w.settled key)
      (when (or (= (?. w.running :key) key) (= (?. w.background :running :key) key)) :running)
      (when (or (= (?. w.queued :key) key) (= (?. w.background :queued :key) key)) :queued)))

(fn settled? [w key]
  "True once a helper has finished with `key` (done or failed)."
  (not= nil (. w.settled key)))

(fn ready? [w key source-fn ?background?]
  "True when the player may compile the shader of plan `key` now: its helper has
finished (or warming is off). Otherwise asks for a helper and returns false:
`(source-fn)` gives the shader's text, or nil and a message (then the player compiles
it and shows the message). A request of the edit lane (the default: a shader the
player must show next) cancels the background lane (cancel-background!) and waits
only for an edit before it; `?background?` (the folded shader, the still's) queues it
in the background lane."
  (if (not w.enabled?) true
      (settled? w key) true
      (status w key) false
      (case (source-fn)
        source (let [lane (if ?background? w.background w)]
                 (when (not ?background?) (cancel-background! w))
                 (set lane.queued {: key : source})
                 (poll! w)
                 false)
        _ (do (settle! w key :failed) true))))

{: new : prepare! : ready? : settled? : poll! : status : cancel-background! : helper-command
 : job-path : write-whole! : remove-jobs!
 : cache-shared? : shell-quote}

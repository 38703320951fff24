;; Scene files are evaluated in a worker process (src/scene/worker-main.fnl), never in
;; the app's: parsing, compiling and running a file and its functions of time. The
;; worker runs with limits the kernel enforces (src/util/confine.fnl) and deadlines
;; here, in its CPU time, past which it is killed: a scene stuck in one C call, or one that
;; allocates past the worker's address space, ends the worker, not the app. The next
;; request starts a new one. What comes back is plain data, read by a strict parser
;; (src/util/wire.fnl), never by `load`.
;;
;; A process has one worker, started with its first load (about 0.3 s). A loaded
;; scene's functions of time stay in the worker; the scene here lists their field
;; paths under :animated, and `animate` asks the worker for their values. A worker
;; that was killed is started again and loads the scene's text again when asked.
;;
;; Without LuaJIT's FFI on Linux the worker cannot be started, and scenes load in this
;; process, inside the sandbox only (a line on standard error says so once).

(local process (require :src.util.process))
(local wire (require :src.util.wire))
(local filestat (require :src.util.filestat))
(local scene-mod (require :src.scene.load))
(local answer-check (require :src.scene.answer))

;; Seconds of the worker's CPU before it is killed. A start compiles the loader (0.3 s
;; under LÖVE here); a load of 1,000,000 spheres made by a loop takes about 4 s (the
;; loop 1.9 s; the sandbox lets a scene's code take 20 million steps and 500 more for
;; each KB it builds, at most about 6 s); one frame of functions of time is held to 1
;; million steps (about 11 ms).
(local deadlines {:start 10 :load 20 :animate 1})
;; The deadlines count the worker's CPU time (from /proc), not the wall clock: on a
;; machine shared with other work a load may wait for a core without being stuck,
;; and a call that never returns spends CPU all the same. A worker that spends
;; neither and answers nothing is stopped after this many times its deadline in
;; wall-clock time.
(local wall-factor 6)

;; The request that loaded each scene, to load it again in a new worker.
(local requests (setmetatable {} {:__mode :k}))

(local state {:worker nil    ; {:child :info :scene :request :in-flight}
              :argv nil      ; how to start it (see `command`)
              :said-fallback? false
              ;; a large answer's decoded copy to collect once its load has returned
              :collect? false})

(fn game-root []
  ;; The folder of this checkout, from this file's path (plain LuaJIT runs from it).
  (let [source (. (debug.getinfo 1 :S) :source)
        path (source:match "^@(.*)src/scene/worker%.fnl$")]
    (if (or (= path nil) (= path "")) "." (path:gsub "/$" ""))))

(fn words [s]
  (icollect [w (s:gmatch "%S+")] w))

(fn command []
  "The command that starts a worker: under LÖVE the same game with --scene-worker
(conf.lua then loads nothing else), under plain LuaJIT tools/scene-worker.fnl.
Another is set with `set-command!` or the environment's RAYMARCHER_SCENE_WORKER
(words split at spaces; tests stand in a worker that hangs)."
  (or state.argv
      (case (os.getenv "RAYMARCHER_SCENE_WORKER")
        (where s (s:match "%S")) (words s))
      (if (and _G.love love.filesystem)
          [(or (process.self-exe) "love") (love.filesystem.getSource) "--scene-worker"]
          (let [root (game-root)]
            [(or (process.self-exe) "luajit") (.. root "/tools/fnl.lua") (.. root "/tools/scene-worker.fnl")]))))

(fn set-command! [argv]
  "Start workers with `argv` from now on (tests); nil for the default."
  (set state.argv argv))

(fn kill! []
  "End the worker now (the next request starts another)."
  (case state.worker
    w (do (process.kill! w.child) (set state.worker nil))))

(fn request! [w value]
  (let [(data err) (wire.encode value)]
    (if (not data) (values nil err)
        (process.send! w.child data (+ (filestat.monotonic) (* wall-factor deadlines.load))))))

(fn budget [w seconds]
  ;; What one request may spend: `seconds` of the worker's CPU from now, and
  ;; wall-factor times that on the clock.
  {: seconds :cpu0 (or (process.cpu-seconds w.child) 0)
   :wall-end (+ (filestat.monotonic) (* wall-factor seconds))})

(fn spent [w b]
  ;; :timeout when the request has spent its CPU, :stalled its wall-clock time.
  (if (> (- (or (process.cpu-seconds w.child) b.cpu0) b.cpu0) b.seconds) :timeout
      (> (filestat.monotonic) b.wall-end) :stalled))

(fn receive-waiting! [w b ?until]
  ;; The next frame from the worker, looking every 50 ms whether the request has
  ;; spent its budget `b` (nil and :timeout or :stalled). With `?until` (a time on
  ;; the monotonic clock), nil and :waiting once it passes; without, state.on-wait
  ;; is called every 50 ms, and when it returns true (the user asked to quit), nil
  ;; and :cancelled.
  (var result nil)
  (while (= nil result)
    (let [slice (math.min (+ (filestat.monotonic) 0.05) b.wall-end (or ?until math.huge))
          (data why) (process.receive! w.child slice)]
      (if data (set result [data])
          (not= why :timeout) (set result [nil why])
          (let [over (spent w b)]
            (if over (set result [nil over])
                (and ?until (>= (filestat.monotonic) ?until)) (set result [nil :waiting])
                (and (not ?until) state.on-wait (state.on-wait)) (set result [nil :cancelled]))))))
  (values (. result 1) (. result 2)))

(fn set-waiting! [f]
  "Call `f` every 50 ms while a load waits for the worker (the player handles its
events there); when it returns true the load is given up and the worker killed.
nil: wait without calling anything."
  (set state.on-wait f))

(fn answer [w b ?until]
  ;; The worker's next answer within budget `b` (see receive-waiting!): a table, or
  ;; nil and :timeout, :stalled, :waiting, :closed, :cancelled or a message.
  (case (receive-waiting! w b ?until)
    data (case (do (set w.answer-bytes (length data)) (wire.decode data))
           (nil err) (values nil err)
           value (if (= (type value) :table) value
                     (values nil "malformed data: the answer is not a table")))
    (nil why) (values nil why)))

(fn start []
  ;; A running worker, or nil and a message.
  (case state.worker
    w w
    _ (let [argv (command)]
        (case (process.spawn argv)
          (nil err) (values nil err)
          child (let [w {: child}]
                  (case (answer w (budget w deadlines.start))
                    (where info info.ready) (do (set w.info info) (set state.worker w) w)
                    (_ why) (do (process.kill! child)
                                (values nil (.. "the scene worker did not start ("
                                                (table.concat argv " ") "): "
                                                (if (= why :timeout) (.. "no answer after " deadlines.start " s of CPU")
                                                    (= why :stalled) (.. "no answer within " (* wall-factor deadlines.start) " s")
                                                    (= why :cancelled) "cancelled"
                                                    (= why :closed) "it ended at once"
                                                    (tostring why)))))))))))

(fn info []
  "What the running worker gave up ({:applied [...] :missing [...] :limits {...}}), or
nil when none is running."
  (?. state.worker :info))

;; Signals that end a worker, and what they mean for it (see src/util/confine.fnl).
(local signal-meanings
  {6 "SIGABRT: it aborted (LuaJIT's panic: out of memory?)"
   9 "SIGKILL: killed from outside (the system's out-of-memory killer?)"
   11 "SIGSEGV: it crashed"
   7 "SIGBUS: it crashed"
   24 "SIGXCPU: past its CPU limit"
   31 "SIGSYS: a system call its filter kills"})

(fn ending [how limits]
  ;; How a worker that closed its connection ended (process.ended), said in words.
  (let [past (.. "its limits: " (or (?. limits :memory-mb) "?") " MB of memory, "
                 (or (?. limits :cpu-seconds) "?") " s of CPU")]
    (case how
      {: signal} (.. "ended by signal " signal ", "
                     (or (. signal-meanings signal) "none of its own limits") "; " past)
      {: code} (.. "exited with status " code "; " past)
      _ (.. "closed its connection and still ran; " past))))

(fn failure [w why file what seconds]
  ;; The message for a request that got no answer; the worker is gone after it.
  ;; (How it ended is asked before it is killed: a closed connection's worker is
  ;; ending, or has ended, on its own.)
  (local how (when (= why :closed) (process.ended w.child 0.5)))
  (process.kill! w.child)
  (set state.worker nil)
  (let [limits (?. w.info :limits)]
    (scene-mod.safe-message
     (.. file ": " (if (= why :timeout)
                       (.. what " took more than " seconds " s of CPU (a library call that never returns?); the scene worker was stopped")
                       (= why :stalled)
                       (.. what " got no answer within " (* wall-factor seconds) " s; the scene worker was stopped")
                       (= why :cancelled)
                       (.. what " was cancelled; the scene worker was stopped")
                       (= why :closed)
                       (.. "the scene worker ended while " what " (" (ending how limits) ")")
                       (.. "the scene worker's answer was refused: " (tostring why)))))))

(fn settle! [w]
  ;; Wait out an animate still in flight (its answer is dropped). True, or nil when
  ;; the worker had to be killed.
  (case w.in-flight
    f (do (set w.in-flight nil)
          (case (answer w f.budget)
            (nil why) (do (failure w why "" "" 0) nil)
            _ true))
    _ true))

(fn valid-answer? [value]
  ;; {:ok false :message M} or {:ok true ...}: the scene itself is src/scene/answer.fnl's
  ;; to check.
  (and (= (type value) :table)
       (or (and (= value.ok false) (= (type value.message) :string))
           (= value.ok true))))

(fn worker-message [message]
  ;; A message the worker sends: text from a process that runs scene code, shown
  ;; escaped and shortened like any loader message.
  (scene-mod.safe-message message))

(fn refuse! [w message]
  ;; An answer that is not what the loader gives: the worker is not to be trusted
  ;; again. The message, the worker gone.
  (process.kill! w.child)
  (when (= state.worker w) (set state.worker nil))
  message)

(fn in-process [source file ?options]
  (when (not state.said-fallback?)
    (set state.said-fallback? true)
    (io.stderr:write "note: the scene worker cannot run here; scene files run inside the sandbox in this process\n"))
  (scene-mod.load-string source file ?options))

;; An answer this large (bytes; 100,000 spheres send 13 MB) ends a worker that holds
;; no functions of time once it is read (see load-code).
(local big-answer (* 32 1024 1024))

(fn checked-answer [w value file source]
  ;; The scene of answer `value` checked as the loader checks a file, and rebuilt by
  ;; it (src/scene/answer.fnl), or nil and a message. After a large answer (past
  ;; big-answer bytes) what is garbage goes at once, before the next copy is built:
  ;; the answer's text before the check, the decoded answer after it, in load-source
  ;; (1,000,000 spheres: 140 and 450 MB). A worker without functions of time to run,
  ;; which keeps the memory it grew to (530 MB), is ended: the next load starts another.
  (let [big? (> w.answer-bytes big-answer)]
    (when big?
      (when (or (not= (type value.animated) :table) (= nil (next value.animated)))
        (kill!))
      (collectgarbage))
    ;; The decoded answer is collected once load-code has returned (its frame holds it).
    (set state.collect? big?)
    (answer-check.check-scene value file source)))

(fn load-code [source file ?options]
  ;; Scene `source` evaluated in the worker (see load-source).
  (case (start)
    (nil err) (values nil (scene-mod.safe-message (.. file ": " err)))
    w (let [request {:op :load : source : file :overrides (?. ?options :overrides)}]
        (if (not (settle! w))
            (load-code source file ?options)
            (do (set w.scene nil)
                (case (request! w request)
                  (nil why) (values nil (failure w why file "sending the scene" deadlines.load))
                  _ (case (answer w (budget w deadlines.load))
                      (nil why) (values nil (failure w why file "loading the scene" deadlines.load))
                      value (if (not (valid-answer? value))
                                (values nil (failure w "the answer is not a scene" file "" 0))
                                (= value.ok false) (values nil (worker-message value.message))
                                ;; Checked as the loader checks a file, and rebuilt by it.
                                (case (checked-answer w value file source)
                                  (nil msg) (values nil (refuse! w msg))
                                  scene (do (set w.scene scene)
                                            (tset requests scene request)
                                            scene))))))))))

(fn load-source [source file ?options]
  "Evaluate scene `source` (named `file` in messages) in the worker and validate it,
as scene-mod.load-string does (same `?options`, same results): the scene, or nil and
a message. A scene the worker had to stop is refused with a message that says why."
  (if (not (process.supported?))
      (in-process source file ?options)
      ;; A file of plain data runs nothing: read here (src/scene/data.fnl), it skips
      ;; sending 6 MB each way and the worker's copy of the scene.
      (case (scene-mod.load-data source file)
        (nil msg) (values nil msg)
        (where scene scene) (do (case state.worker w (settle! w)) scene)
        _ (let [(scene err) (load-code source file ?options)]
            (when state.collect?
              (set state.collect? false)
              (collectgarbage))
            (values scene err)))))

(fn load-file [path ?read ?options]
  "Read the scene file at `path` (with `?read`, default scene-mod.read-capped) and load
it in the worker (see load-source)."
  (let [(source err) ((or ?read scene-mod.read-capped) path)]
    (if source
        (load-source source path ?options)
        (values nil (scene-mod.safe-message (.. path ": cannot read the scene file: "
                                                (tostring (or err "no such file"))))))))

(fn own? [scene]
  ;; Whether the worker's functions of time belong to `scene` (a scene loaded in
  ;; this process has its functions under :animated).
  (and scene.animated (= nil (?. scene.animated 1 :f))))

(fn ensure-loaded [scene]
  ;; The worker, holding `scene`'s functions of time (loading its text again after a
  ;; restart or another load); or nil and a message.
  (case (start)
    (nil err) (values nil err)
    w (if (= w.scene scene) w
          (let [req (. requests scene)]
            (if (not (and req (= req.file scene.file)))
                (values nil (.. scene.file ": the scene worker no longer has this scene's functions of time"))
                (case (request! w req)
                  (nil why) (values nil (failure w why scene.file "loading the scene again" deadlines.load))
                  _ (case (answer w (budget w deadlines.load))
                      (nil why) (values nil (failure w why scene.file "loading the scene again" deadlines.load))
                      {:ok true} (do (set w.scene scene) w)
                      (where {: message} (= (type message) :string)) (values nil (worker-message message))
                      _ (values nil (failure w "the answer is not a scene" scene.file "" 0)))))))))

(fn apply-values! [w scene value]
  ;; The worker's values checked (src/scene/answer.fnl) and set: true, or nil and a
  ;; message (the worker killed when its answer is refused).
  (if (and (= value.ok false) (= (type value.message) :string))
      (values nil (worker-message value.message))
      (case (if (= value.ok true) (answer-check.check-values scene value.values)
                (values nil (scene-mod.safe-message
                             (.. scene.file ": the scene worker's answer was refused: not values"))))
        (nil msg) (values nil (refuse! w msg))
        checked (do (each [i a (ipairs scene.animated)]
                      (let [(target key) (scene-mod.target-of scene a.path)]
                        (tset target key (. checked i))))
                    true))))

(fn request-animate! [scene t]
  "Ask the worker for the values of `scene`'s functions of time at `t` seconds without
waiting (see poll-animate!). True, or nil and a message. (A scene loaded in this
process is animated here and now.)"
  (if (not (own? scene))
      (do (set state.local [scene (scene-mod.animate scene t)]) true)
      (case (ensure-loaded scene)
        (nil err) (values nil err)
        w (if (not (settle! w)) (request-animate! scene t)
              (case (request! w {:op :animate : t})
                (nil why) (values nil (failure w why scene.file (.. "the functions of time (t = " (scene-mod.time-text t) ")") deadlines.animate))
                _ (do (set w.in-flight {: scene : t :budget (budget w deadlines.animate)})
                      true))))))

(fn poll-animate! [scene ?wait]
  "The answer to request-animate!, waiting at most `?wait` seconds (default 0): true
once `scene` has its values for that time, :pending while the worker is still at it,
or nil and a message (the worker was killed when past its deadline: a second of
its CPU)."
  (case (?. state.worker :in-flight)
    (where nil (= (?. state.local 1) scene))
    (let [[_ ok? err] state.local]
      (set state.local nil)
      (values ok? err))
    nil (values nil "no values were asked for")
    f (let [w state.worker]
        (case (answer w f.budget (+ (filestat.monotonic) (or ?wait 0)))
          (nil :waiting) :pending
          (nil why) (do (set w.in-flight nil)
                        (values nil (failure w why scene.file (.. "the functions of time (t = " (scene-mod.time-text f.t) ")") deadlines.animate)))
          value (do (set w.in-flight nil)
                    (if (not= f.scene scene) (values nil "the values are for another scene")
                        (apply-values! w scene value)))))))

(fn animate [scene t]
  "Set `scene`'s functions of time to their values at `t` (waiting for the worker, at
most a second of its CPU): true, or nil and a message. A scene loaded in this process (by
scene-mod) is animated here, as scene-mod.animate does."
  (if (not (own? scene)) (scene-mod.animate scene t)
      (case (request-animate! scene t)
        (nil err) (values nil err)
        _ (poll-animate! scene (* wall-factor deadlines.animate)))))

{: load-source : load-file : animate : request-animate! : poll-animate! : kill!
 : info : set-command! : set-waiting! : command : deadlines}

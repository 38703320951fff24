;; The scene worker: the child process that parses, compiles and runs scene files and
;; their functions of time (src/scene/worker.fnl starts it and talks to it). It loads
;; its modules, gives up what it does not need (src/util/confine.fnl: address space,
;; CPU per request, files, new privileges, a seccomp filter), says it is ready, then
;; answers requests on its standard input, one frame each (src/util/wire.fnl data),
;; until that input ends:
;;
;;   {:op :load :source TEXT :file NAME :overrides {...}}
;;       -> {:ok true :scene SCENE :animated [PATH ...]} or {:ok false :message M}
;;   {:op :animate :t SECONDS}
;;       -> {:ok true :values [V ...]} (one per path, in order) or {:ok false :message M}
;;
;; The scene's own sandbox (src/scene/sandbox.fnl) still runs inside: the worker is a
;; second wall around it, not a replacement.

(local scene-mod (require :src.scene.load))
(local wire (require :src.util.wire))
(local confine (require :src.util.confine))
(local strategies (require :src.sdf.strategies))
;; `pairs` under another name: a loop over `pairs` by that name is LuaJIT's ITERN,
;; which Debian 12's LuaJIT ends early once despecialised (see src/util/wire.fnl).
(local each-pair pairs)

;; Limits of the worker as a whole (the sandbox's are smaller: 512 MB of Lua memory
;; while a scene runs, 128 MB while it compiles).
(local limits
  {;; Address space: LÖVE with no modules and LuaJIT map about 40 MB; a scene of
   ;; 1,000,000 spheres made by a loop peaks at 1.3 GB resident (its own tables,
   ;; the checked copy and the encoded answer, 90 MB); 1024 MB is not enough.
   :memory-mb 1536
   ;; CPU a request may take: a load of 1,000,000 spheres takes about 4 s here;
   ;; the sandbox's own backstop grows with the scene's steps.
   :cpu-seconds 30
   ;; Memory the functions of time may keep between frames (the sandbox's memory
   ;; limit for a scene's code: what one call may build).
   :kept-mb 96})

;; An answer this large (bytes) has its tables collected before it is written.
(local large-answer (* 16 1024 1024))

(var current nil)   ; the last scene loaded, with its functions of time
(var current-mb nil)  ; Lua memory in use with it loaded (MB), from its first frame

(fn read-frame [input]
  ;; One frame from `input` (a file): the payload, or nil at the end.
  (let [line (input:read "*l")
        n (and line (line:match "^%d+$") (tonumber line))]
    (when n
      (let [payload (if (= n 0) "" (input:read n))]
        (when (and payload (= (length payload) n)) payload)))))

(fn encoded [value]
  ;; `value` as wire parts and their size (a refusal when it cannot be sent).
  (case (wire.encode-parts value)
    (nil err) (wire.encode-parts {:ok false :message (.. "the worker could not send its answer: " err)})
    (parts size) (values parts size)))

(fn write! [output parts size]
  ;; As wire.frame has it, without joining the parts or copying the data (a million
  ;; objects: 140 MB).
  (output:write size "\n")
  (each [_ part (ipairs parts)] (output:write part))
  (output:flush))

(fn answer! [output value]
  (write! output (encoded value)))

(fn sendable [scene]
  ;; The scene as plain data: its functions of time stay here; their paths go.
  (let [copy (collect [k v (each-pair scene)] (when (not= k :animated) (values k v)))]
    (values copy (icollect [_ a (ipairs (or scene.animated []))] a.path))))

(fn out-of-memory? [message]
  ;; LuaJIT's message when an allocation fails: here, past the address space.
  (not= nil (string.find (tostring message) "not enough memory" 1 true)))

(fn memory-message [file what]
  (scene-mod.safe-message
   (.. file ": " what " more memory than the scene worker has (" limits.memory-mb " MB)")))

(fn load! [request]
  (set current nil)
  (set current-mb nil)
  (let [(ok? scene err) (pcall scene-mod.load-string request.source request.file
                               {:overrides request.overrides})]
    (if (out-of-memory? (if ok? err scene))
        {:ok false :message (memory-message request.file "the scene needs")}
        (not ok?) {:ok false :message (scene-mod.safe-message (.. request.file ": " (tostring scene)))}
        (not scene) {:ok false :message err}
        (let [(data paths) (sendable scene)]
          ;; The scene's own tables (what its code built) are garbage now: gone before
          ;; the answer is encoded, for a large scene's sake (1,000,000 spheres: 340 MB).
          (collectgarbage)
          (set current scene)
          {:ok true :scene data :animated paths}))))

(fn kept-mb []
  ;; Lua memory in use beyond what the loaded scene had: what its functions of time
  ;; keep from one frame to the next. A full collection only when the count (garbage
  ;; included) is past the limit.
  (let [over #(- (/ (collectgarbage :count) 1024) current-mb)]
    (if (<= (over) limits.kept-mb) 0
        (do (collectgarbage) (math.max 0 (over))))))

(fn animate! [request]
  ;; What the scene holds without garbage, measured at its first frame (a full
  ;; collection of a large scene takes several ms, which a load need not pay).
  (when (and current (not current-mb))
    (collectgarbage)
    (set current-mb (/ (collectgarbage :count) 1024)))
  (if (not current) {:ok false :message "no scene is loaded"}
      (let [(ok? done err) (pcall scene-mod.animate current request.t)
            kept (kept-mb)]
        (if (out-of-memory? (if ok? err done))
            {:ok false :message (memory-message current.file "the functions of time need")}
            (not ok?) {:ok false :message (scene-mod.safe-message (tostring done))}
            (not done) {:ok false :message err}
            (> kept limits.kept-mb)
            {:ok false
             :message (scene-mod.safe-message
                       (string.format "%s: the functions of time keep %.1f MB from frame to frame (at t = %s); at most %d MB"
                                      current.file kept (scene-mod.time-text request.t) limits.kept-mb))}
            {:ok true
             :values (icollect [_ a (ipairs (or current.animated []))]
                       (let [(target key) (scene-mod.target-of current a.path)]
                         (. target key)))}))))

(fn handle [request]
  "The answer to one request (a table read from the wire)."
  (if (not= (type request) :table) {:ok false :message "the request is not a table"}
      (= request.op :load)
      (if (and (= (type request.source) :string) (= (type request.file) :string)
               (or (= nil request.overrides) (= (type request.overrides) :table)))
          (load! request)
          {:ok false :message "a load needs :source and :file"})
      (= request.op :animate)
      (if (= (type request.t) :number) (animate! request)
          {:ok false :message "an animate needs :t"})
      {:ok false :message (.. "unknown request " (tostring request.op))}))

(fn serve! [input output]
  "Confine this process, say so on `output`, then answer the requests on `input` until
it ends."
  ;; The drawing strategies load on first use (their files require the emitters,
  ;; which reach objects through them): here, while this process can still list a
  ;; folder and open files (a custom node is lowered when the scene is checked).
  (strategies.all)
  (let [(applied missing) (confine.confine! limits)]
    (answer! output {:ready true : applied : missing :limits limits})
    (var payload (read-frame input))
    (while payload
      (confine.limit-cpu! limits.cpu-seconds)
      (let [(request err) (wire.decode payload)
            load? (= (?. request :op) :load)]
        (set payload nil)
        (var reply (if request (handle request) {:ok false :message err}))
        (let [(parts size) (encoded reply)]
          (set reply nil)
          ;; After a load, what only the answer needed is garbage (the answer's tables,
          ;; and a scene without functions of time, which nothing asks for again). A
          ;; large one is collected before the answer is written, not after: the app
          ;; decodes and checks it while this process would still hold it (1,000,000
          ;; spheres: the worker's 1,047 MB beside the app's 509 MB, over the 1.5 GB
          ;; they share, see test/million_spec.fnl and docs/security.md).
          (when (and load? current (not (scene-mod.animated? current)))
            (set current nil))
          (when (and load? (> size large-answer))
            (collectgarbage))
          (write! output parts size))
        (when load?
          ;; Then the encoded answer. Twice: LuaJIT's string buffer, grown to the
          ;; answer's size, halves at each collection.
          (collectgarbage)
          (collectgarbage)))
      (set payload (read-frame input)))))

(fn run-love! []
  "love.load of the worker: conf.lua calls this with --scene-worker."
  (set love.errorhandler
       (fn [message]
         (io.stderr:write (.. "scene worker: " (tostring message) "\n"))
         (os.exit 1)))
  (set love.load (fn [] (serve! io.stdin io.stdout) (os.exit 0))))

{: serve! : run-love! : handle : limits}

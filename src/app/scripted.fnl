;; Scripts that drive the running player one frame at a time (the input check, the
;; edit-latency measure): a coroutine resumed after every love.update, and the
;; temporary scene file it plays.

(fn temp-scene-path []
  "A fresh path for a temporary scene file (.fnl) in the system's temp folder."
  ;; os.tmpname creates the file it names: take the unique name, remove that file
  ;; (it would be left behind empty), and use the name with .fnl added.
  (let [base (os.tmpname)]
    (os.remove base)
    (.. base ".fnl")))

(fn write! [path text]
  "Write `text` to the file at `path` (an error when it cannot)."
  (with-open [f (assert (io.open path :wb))] (f:write text)))

(fn run-per-frame! [script on-error on-end]
  "Resume `script` (a function; it yields once per frame) after each of the player's
updates. A failure calls `(on-error message)`; when the script has ended (returned
or failed), `(on-end ok?)` runs."
  (let [co (coroutine.create script)
        update love.update]
    (set love.update
         (fn [dt]
           (update dt)
           (let [(ok? err) (coroutine.resume co)]
             (when (not ok?)
               (on-error (debug.traceback co (tostring err))))
             (when (not= (coroutine.status co) :suspended)
               (on-end ok?)))))))

{: temp-scene-path : write! : run-per-frame!}

;; Watching one scene file for edits. Pure: the file's stat and the clock are passed in,
;; so the settling rules are tested without a file system. A change is reported only
;; once the file has stayed the same for a while, so editors that save by truncating
;; and writing, or by writing a temp file and renaming it over, never show their
;; half-written moment.

(local settle-seconds 0.2)     ; unchanged this long after an edit: load it
(local missing-seconds 1.0)    ; gone this long: report it deleted (a rename is quicker)

(fn signature [info]
  (and info (.. (tostring info.mtime) ":" (tostring info.size) ":" (tostring info.content))))

(fn new [info]
  "A watcher whose last loaded version of the file is `info` ({:mtime :size :content},
or nil when the file is missing)."
  {:loaded (signature info) :seen (signature info) :seen-at nil :missing-since nil
   :reported-missing? false})

(fn poll! [w info now]
  "Feed the file's current `info` (nil when missing) at time `now` (seconds).
Returns :changed when a new version has settled and should be loaded, :deleted once
when the file has been gone for a second, else :idle."
  (if (= info nil)
      (do (when (= w.missing-since nil) (set w.missing-since now))
          (set w.seen nil)
          (if (and (not w.reported-missing?) (>= (- now w.missing-since) missing-seconds))
              (do (set w.reported-missing? true) :deleted)
              :idle))
      (let [sig (signature info)]
        (set w.missing-since nil)
        (set w.reported-missing? false)
        (if (not= sig w.seen)
            (do (set w.seen sig) (set w.seen-at now) :idle)
            (and (not= sig w.loaded) (>= (- now w.seen-at) settle-seconds))
            (do (set w.loaded sig) :changed)
            :idle))))

(fn loaded! [w info]
  "Record `info` as the version now loaded (after a reload or a scene switch)."
  (set w.loaded (signature info))
  (set w.seen w.loaded)
  (set w.missing-since nil)
  (set w.reported-missing? false))

{: new : poll! : loaded! : settle-seconds : missing-seconds}

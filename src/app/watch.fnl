;; Watching one scene file for edits. Pure: the file's state and the clock are passed
;; in, so the rules are tested without a file system. A new version is loaded only
;; once the file itself has not been written for a while (its modification time is
;; that far in the past), so editors that save by truncating and writing, or by
;; writing a temp file and renaming it over, never show their half-written moment,
;; however rarely the player gets to look.

(local settle-seconds 0.2)     ; not written for this long: load it
(local missing-seconds 1.0)    ; gone or unreadable this long: say so (a rename is quicker)

(fn signature [info]
  (and info (not info.problem)
       (.. (tostring info.mtime) ":" (tostring info.size) ":" (tostring info.content))))

(fn new [info]
  "A watcher whose last loaded version of the file is `info` ({:mtime :size :content},
`:coarse? true` when the time has whole seconds only; nil when the file is missing)."
  {:loaded (signature info) :seen (signature info) :missing-since nil
   :reported-missing? false :problem nil})

(fn settled? [info now]
  "True when the file was last written at least settle-seconds before `now`. With
whole-second times the write may have happened up to a second after the stamp."
  (>= (- now info.mtime (if info.coarse? 1 0)) settle-seconds))

(fn poll! [w info now]
  "Feed the file's current `info` at time `now` (seconds, the clock of its mtime):
a table {:mtime :size :content}, {:problem \"it is a directory\"} when it cannot be
read, or nil when it is missing. Returns :changed when a new version has settled and
should be loaded, :deleted or :unreadable once when the file has been gone or
unreadable for a second (w.problem says why), else :idle. Read the content before
the time, so a write during the read shows in the time."
  (if (or (= info nil) info.problem)
      (do (when (= w.missing-since nil) (set w.missing-since now))
          (set w.seen nil)
          (set w.problem (and info info.problem))
          (if (and (not w.reported-missing?) (>= (- now w.missing-since) missing-seconds))
              (do (set w.reported-missing? true) (if info :unreadable :deleted))
              :idle))
      (let [sig (signature info)]
        (set w.missing-since nil)
        (set w.reported-missing? false)
        (set w.problem nil)
        (set w.seen sig)
        (if (and (not= sig w.loaded) (settled? info now))
            (do (set w.loaded sig) :changed)
            :idle))))

(fn loaded! [w info]
  "Record `info` as the version now loaded (after a reload or a scene switch)."
  (set w.loaded (signature info))
  (set w.seen w.loaded)
  (set w.missing-since nil)
  (set w.reported-missing? false))

{: new : poll! : loaded! : settle-seconds : missing-seconds}

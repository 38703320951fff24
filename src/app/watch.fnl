;; Watching one scene file for edits. Pure: the file's state and the clock are passed
;; in, so the rules are tested without a file system. A new version is loaded only
;; once the file itself has not been written for a while (its modification time is
;; that far in the past), so editors that save by truncating and writing, or by
;; writing a temp file and renaming it over, never show their half-written moment,
;; however rarely the player gets to look.
;;
;; A load may still read the file in the middle of a write (a load that does not come
;; from the watcher, such as one finishing after a compile, or a writer that pauses
;; longer than the settle time): a read that does not load is reported only when the
;; file stayed the same through it and for retry-seconds before it (failure-stands?);
;; else the watcher loads it again once it has stayed the same that long (retry!).

;; Not written for this long: load it. An editor's save (one write, or a temporary
;; file renamed over) takes well under a millisecond for a scene file; a writer that
;; pauses longer is caught by the retry below. The kernel stamps the time from a clock
;; that ticks every 1-10 ms, at or before the write: 10 ms after the stamp the write
;; is at least that tick's remainder past. With the player looking 100 times a
;; second, an edit is read 10-20 ms after its save (it was 0.2 s, then 0.03 s: 20 ms
;; of a value edit's 0.1 s to its picture went here).
(local settle-seconds 0.01)
(local missing-seconds 1.0)    ; gone or unreadable this long: say so (a rename is quicker)
(local retry-seconds 0.15)     ; a failed read counts once the file stayed the same this long

(fn signature [info]
  (and info (not info.problem)
       (.. (tostring info.mtime) ":" (tostring info.size) ":" (tostring info.content))))

(fn new [info]
  "A watcher whose last loaded version of the file is `info` ({:mtime :size :content},
`:coarse? true` when the time has whole seconds only; nil when the file is missing)."
  {:loaded (signature info) :seen (signature info) :missing-since nil
   :reported-missing? false :problem nil :retry? false})

(fn settled? [info now ?seconds]
  "True when the file was last written at least `?seconds` (settle-seconds) before
`now`. With whole-second times the write may have happened up to a second after the
stamp."
  (>= (- now info.mtime (if info.coarse? 1 0)) (or ?seconds settle-seconds)))

(fn failure-stands? [before after now]
  "A load of the file failed: true when that is the file's own failure, to report
now; false when the read may have caught a write (retry! then). `before` and `after`
are the file's info ({:mtime :size :content}, nil when missing) just before and just
after the read, `now` the time after it. It stands when the file was the same
before and after (its time, size and text, or missing both times) and had not been
written for retry-seconds."
  (if (and (= nil before) (= nil after)) true          ; missing both times
      (or (= nil before) (= nil after)) false            ; came or went meanwhile
      (or before.problem after.problem) (= before.problem after.problem)
      (and (= (signature before) (signature after))
           (settled? after now retry-seconds))))

(local tick-seconds 0.02)   ; longer than the kernel's clock tick for file times

(fn read-again? [last st]
  "Whether a look at the file must read its text again: `st` is its stat now
({:kind :mtime :size :ino :dev :coarse?}, nil when missing), `last` what the last
read saw ({:mtime :size :ino :dev :read-at}, the wall-clock time the read began;
nil when there was none). Not when its time, size and inode are those of that read
and the read began tick-seconds after that time: the kernel stamps a write with a
clock that ticks every few milliseconds, so a later write has a later time, but two
writes within one tick may share one. Always with whole-second times."
  (not (and st last (= st.kind :file) (not st.coarse?) (= st.mtime last.mtime)
            (= st.size last.size) (= st.ino last.ino) (= st.dev last.dev)
            (> last.read-at (+ st.mtime tick-seconds)))))

(fn retry! [w]
  "The last load read the file mid-write (see failure-stands?): poll! says :changed
once the file has stayed the same for retry-seconds, even when its text is the one
loaded."
  (set w.retry? true))

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
        (if (and w.retry? (settled? info now retry-seconds))
            (do (set w.retry? false) (set w.loaded sig) :changed)
            (and (not= sig w.loaded) (settled? info now))
            (do (set w.retry? false) (set w.loaded sig) :changed)
            :idle))))

(fn loaded! [w info]
  "Record `info` as the version now loaded (after a reload or a scene switch)."
  (set w.loaded (signature info))
  (set w.seen w.loaded)
  (set w.missing-since nil)
  (set w.reported-missing? false)
  (set w.retry? false))

{: new : poll! : loaded! : failure-stands? : retry! : read-again? : settle-seconds
 : missing-seconds : retry-seconds}

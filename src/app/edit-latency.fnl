;; `love . --edit-latency SCENE [--sync-compile]`: how long the player takes to show an
;; edit of the scene file, and how long its window stops answering meanwhile. The
;; player runs SCENE (a copy in a temporary file) in a 640x360 window; the edits are
;; a structural one (a small sphere added to the scene's objects: a new shader) and
;; then a value one (that sphere's colour). The watcher's 0.2 s of settling is skipped, as in the
;; soak test. Prints, for each edit, the time from the write to the end of the first
;; frame drawn with it, and the longest frame in between (the window's freeze).
;; With the compile helper (the default) the window keeps drawing the last scene;
;; with --sync-compile the player compiles it itself. tools/edit-latency.sh runs both
;; for the showcase scenes, each with an empty shader cache.

(local play (require :src.app.play))
(local files (require :src.util.files))
(local filestat (require :src.util.filestat))
(local scripted (require :src.app.scripted))
(local write! scripted.write!)

(fn with-sphere [text color]
  ;; The scene's own text, evaluated as it is, with one more top-level object.
  (.. "(let [scene (do " text "\n)]\n  (table.insert scene.objects {:kind :sphere :radius 0.05 :pos [0 0 -50] :color "
      color "})\n  scene)\n"))

(fn script [path text o report]
  (let [state play.state
        frames []                       ; the time at the start of each update
        wait (fn [] (coroutine.yield) (table.insert frames (love.timer.getTime)))]
    (for [_ 1 5] (wait))
    (fn edit! [label new-text shown?]
      (let [start (love.timer.getTime)
            first (+ (length frames) 1)
            until (+ start 600)]
        (write! path new-text)
        (play.poll-file! (+ (filestat.now) 0.05))
        (play.poll-file! (+ (filestat.now) 0.3))
        ;; The frame that drew the edit ends before the next update starts.
        (while (and (not (shown?)) (< (love.timer.getTime) until)) (wait))
        (wait)
        (var longest 0)
        (var prev start)
        (for [i first (length frames)]
          (set longest (math.max longest (- (. frames i) prev)))
          (set prev (. frames i)))
        (report label (* 1000 (- (. frames (length frames)) start)) (* 1000 longest)
                (if (shown?) "" "  (not shown within 600 s)"))))
    (let [old state.scene]
      (edit! "structural edit (a sphere added)" (with-sphere text "[1 1 1]")
             #(and (not= state.scene old) (= (?. state.drawn :scene) state.scene)))
      (let [before state.scene]
        (edit! "value edit (its colour)" (with-sphere text "[0.5 0.9 0.2]")
               #(and (not= state.scene before) (= (?. state.drawn :scene) state.scene)))))))

(fn run [o]
  "Play a copy of `o.scene`, edit it twice and print the latencies; quits 0, or 1
when the scene cannot be read."
  (let [text (files.read-user o.scene)
        path (scripted.temp-scene-path)]
    (if (not text)
        (do (io.stderr:write (.. "error: " o.scene ": cannot read the scene file\n"))
            (love.event.quit 1))
        (do (write! path text)
            (love.window.setMode 640 360)
            (set play.state.quiet? true)
            (play.start! {:scene path :frames 0 :warm? (not o.sync-compile?)})
            (scripted.run-per-frame!
              #(script path text o
                       (fn [label ms longest note]
                         (print (string.format "%s %s, %s: shown after %.0f ms, longest frame %.0f ms%s"
                                               o.scene label
                                               (if (?. play.state.warm :enabled?) "compile helper"
                                                   "compiled in the player")
                                               ms longest note))))
              #(io.stderr:write (.. "error: " $ "\n"))
              (fn [ok?]
                (os.remove path)
                (love.event.quit (if ok? 0 1))))))))

{: run}

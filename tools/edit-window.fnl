;; luajit tools/fnl.lua tools/edit-window.fnl --edit FILE EDIT
;; The text of scene FILE after EDIT, as a person would type it: an object written
;; into the file's :objects vector (the scene stays plain data when it was), 4 units
;; in front of the camera (src/render/camera.fnl's forward):
;;   added      a magenta sphere
;;   kind       the same made a box
;;   operation  that box twisted
;;   value      that box green (a value edit: the same shader)
;; A file whose objects are not a literal vector gets the object from code around it.
;;
;; luajit tools/fnl.lua tools/edit-window.fnl DIR LOG SCENE EDIT
;; Reads what tools/edit-window.sh left in DIR for one edit of one scene and prints
;; one line of the table:
;;   LOG              the player's RAYMARCH_FRAME_LOG: "time kind serial" a frame
;;   DIR/save         the wall-clock time just before the edit was written
;;   DIR/grabs        "index start end" for each window grab DIR/NNNN.xwd
;; From the log: the first frame after the save that shows another scene (the new
;; one) and what drew it, the first frame its own shader drew, the longest time
;; between two frames from the save until then, and frames that went back to the old
;; scene. From the grabs, as a person would see it: the first grab whose middle (half
;; the width and height, where the edited object is) differs from the last grab
;; before the save (over `changed-fraction` of its pixels by more than `changed-step`
;; in a channel), and grabs after it that match the old picture again. Only the
;; middle: the player's messages show at the top (with the HUD, even while it is
;; hidden) and at the bottom.

(local states (require :src.verify.states))
(local scene-load (require :src.scene.load))
(local camera (require :src.render.camera))

(local changed-step 40)        ; of 255: well above llvmpipe's noise (none: a picture
                               ; drawn twice is the same bytes) and a coarse
                               ; picture's blur of an unchanged edge is below it
(local changed-fraction 0.001) ; of the middle's pixels: the added object covers a
                               ; fifth of them or more

(fn read-lines [path]
  (let [f (assert (io.open path :r))
        lines (icollect [line (f:lines)] line)]
    (f:close)
    lines))

(fn frames-of [path]
  (icollect [_ line (ipairs (read-lines path))]
    (let [(t kind serial) (line:match "^(%S+) (%S+) (%S+)$")]
      (when t {:t (tonumber t) : kind :serial (tonumber serial)}))))

(fn grabs-of [dir]
  (icollect [_ line (ipairs (read-lines (.. dir "/grabs")))]
    (let [(i t0 t1) (line:match "^(%d+) (%S+) (%S+)$")]
      (when i {:path (string.format "%s/%04d.xwd" dir (tonumber i))
               :t0 (tonumber t0) :t1 (tonumber t1)}))))

(fn changed? [a b]
  "True when pictures `a` and `b` differ in more than changed-fraction of the pixels
of their middle (from a quarter to three quarters of the width and the height)."
  (let [x0 (math.floor (/ a.width 4)) x1 (math.floor (* 3 (/ a.width 4)))
        y0 (math.floor (/ a.height 4)) y1 (math.floor (* 3 (/ a.height 4)))
        limit (* changed-fraction (- x1 x0) (- y1 y0))
        differs? (fn [i] (> (math.abs (- (. a.pixels i) (. b.pixels i))) changed-step))]
    (var n 0)
    (for [y y0 (- y1 1)]
      (for [x x0 (- x1 1)]
        (let [i (* 4 (+ x (* y a.width)))]
          (when (or (differs? i) (differs? (+ i 1)) (differs? (+ i 2)))
            (set n (+ n 1))))))
    (> n limit)))

(fn from-log [frames save]
  (let [before (icollect [_ f (ipairs frames)] (when (< f.t save) f))
        old (. before (length before) :serial)
        after (icollect [_ f (ipairs frames)] (when (>= f.t save) f))
        first (accumulate [found nil _ f (ipairs after)]
                (or found (when (not= f.serial old) f)))
        own (when first
              (accumulate [found nil _ f (ipairs after)]
                (or found (when (and (= f.serial first.serial) (= f.kind :shader)) f))))
        ;; (No frame after the save: a player stuck in one frame shows nothing new.)
        stop (or (?. own :t) (?. after (length after) :t) save)]
    (var longest 0)
    (var prev (. before (length before) :t))
    (var back 0)
    (each [_ f (ipairs after)]
      (when (<= f.t stop)
        (set longest (math.max longest (- f.t prev)))
        (set prev f.t))
      (when (and first (> f.t first.t) (= f.serial old)) (set back (+ back 1))))
    {: first : own : longest : back}))

(fn from-grabs [grabs save]
  ;; The last grab that ended before the save is the old picture.
  (let [ref (accumulate [r nil _ g (ipairs grabs)] (if (< g.t1 save) g r))
        old (when ref (assert (states.read-xwd ref.path)))]
    (var first nil)
    (var back 0)
    (var seen 0)
    (when old
      (each [_ g (ipairs grabs)]
        (when (> g.t0 ref.t1)
          (let [img (states.read-xwd g.path)]
            (when img
              (set seen (+ seen 1))
              (if (changed? old img)
                  (when (not first) (set first g))
                  (when first (set back (+ back 1)))))))))
    {: first : back : seen}))

(fn ms [t save] (if t (string.format "%.0f" (* 1000 (- t save))) "-"))

(fn edited [path edit]
  (let [f (assert (io.open path :r))
        text (f:read :*a)
        _ (f:close)
        scene (assert (scene-load.load-string text path))
        cam scene.camera
        ahead (camera.forward cam)
        p (fcollect [i 1 3] (+ (. cam.pos i) (* 4 (. ahead i))))
        pos (string.format "[%.3f %.3f %.3f]" (. p 1) (. p 2) (. p 3))
        object (case edit
                 :added (.. "{:kind :sphere :radius 0.6 :pos " pos " :color [1 0 1]}")
                 :kind (.. "{:kind :box :size [0.5 0.5 0.5] :pos " pos " :color [1 0 1]}")
                 :operation (.. "{:kind :twist :angle 90 :pos " pos
                                " :children [{:kind :box :size [0.3 0.3 0.7] :color [1 0 1]}]}")
                 :value (.. "{:kind :twist :angle 90 :pos " pos
                            " :children [{:kind :box :size [0.3 0.3 0.7] :color [0 0.8 0.2]}]}")
                 _ (error (.. "no edit " (tostring edit))))
        (at stop) (text:find ":objects%s*%[")]
    (if at
        (.. (text:sub 1 stop) object "\n  " (text:sub (+ stop 1)))
        (.. "(let [scene (do\n" text "\n)]\n  (table.insert scene.objects " object ")\n  scene)\n"))))

(when (= (. arg 1) "--edit")
  (io.write (edited (. arg 2) (. arg 3)))
  (os.exit 0))

(let [[dir log-path scene edit] arg
      save (tonumber (. (read-lines (.. dir "/save")) 1))
      log (from-log (frames-of log-path) save)
      screen (from-grabs (grabs-of dir) save)]
  (print (string.format "%-16s %-15s %9s %-12s %9s %9s %6s %15s %6s"
                        scene edit
                        (ms (?. log.first :t) save) (or (?. log.first :kind) "none")
                        (ms (?. log.own :t) save) (string.format "%.0f" (* 1000 log.longest))
                        log.back
                        (if screen.first
                            (.. (ms screen.first.t0 save) "-" (ms screen.first.t1 save))
                            "-")
                        screen.back))
  (when (or (not log.first) (not screen.first) (> log.back 0) (> screen.back 0))
    (os.exit 1)))

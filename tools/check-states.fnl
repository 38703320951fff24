;; The classifier half of tools/check-states.sh: reads the frames grabbed in each
;; scenario (X window dumps or PNGs), says per scenario how many show a mix of
;; scene states (src/verify/states.fnl), and saves the worst one as a PNG.
;;
;;   luajit tools/fnl.lua tools/check-states.fnl [--x1 N] [--y1 N] [--out DIR]
;;          [--min-range DEG] [--two-states NAME,...] NAME=DIR ...
;;   luajit tools/fnl.lua tools/check-states.fnl --calibrate FILE ...
;;
;; NAME=DIR: the frames DIR/*.xwd or DIR/*.png, in name order. --x1 and --y1 bound the
;; region classified (x < x1, y < y1: leaves out the parameter panel and the message
;; area). --min-range: a scenario whose frames' states span fewer degrees of hue did
;; not change state at all (a missed slider, an edit not seen) and is reported as not
;; exercised. --two-states: in these scenarios (one edit) a frame whose state is
;; neither the first frame's nor the last frame's (within the tolerance) is counted as
;; mixed too: a blend of the two pictures (a cross-fade) has one hue throughout, in
;; between. --calibrate prints each file's strip spread. Exit 0: no frame mixes
;; states; 1: some frame does; 2: a scenario was not exercised or a file is unreadable.

(local states (require :src.verify.states))
(local png (require :src.util.png))

(fn fail [msg]
  (io.stderr:write (.. "check-states: " msg "\n"))
  (os.exit 2))

(fn list-frames [dir]
  (let [p (io.popen (.. "ls -1 '" (dir:gsub "'" "'\\''") "' 2>/dev/null"))
        names (icollect [line (p:lines)]
                (when (or (line:match "%.xwd$") (line:match "%.png$")) (.. dir "/" line)))]
    (p:close)
    (table.sort names)
    names))

(fn read-image [path]
  (if (path:match "%.xwd$") (states.read-xwd path) (png.read-file path)))

(fn strip-line [result]
  ;; The strips' states top to bottom, runs of one value written once with their
  ;; length: "144 x40, 215 x110" ("-": no state).
  (let [runs []]
    (each [_ s (ipairs result.strips)]
      (let [v (if s.hue (string.format "%.0f" s.hue) "-")
            last (. runs (length runs))]
        (if (and last (= last.v v))
            (set last.n (+ last.n 1))
            (table.insert runs {: v :n 1}))))
    (table.concat (icollect [_ r (ipairs runs)] (.. r.v " x" r.n)) ", ")))

(fn parse-args [argv]
  (let [o {:scenarios [] :files [] :x1 960 :y1 600 :out "out/check-states" :min-range 30
           :two-states {}}]
    (var i 1)
    (while (<= i (length argv))
      (let [a (. argv i)
            nxt (. argv (+ i 1))]
        (case a
          :--calibrate (set o.calibrate? true)
          (where flag (or (= flag :--x1) (= flag :--y1) (= flag :--min-range)))
          (do (when (not (tonumber nxt)) (fail (.. flag " needs a number")))
              (tset o (flag:sub 3) (tonumber nxt))
              (set i (+ i 1)))
          :--two-states (do (when (not nxt) (fail "--two-states needs scenario names"))
                            (each [name (nxt:gmatch "[^,]+")] (tset o.two-states name true))
                            (set i (+ i 1)))
          :--out (do (when (not nxt) (fail "--out needs a directory"))
                     (set o.out nxt)
                     (set i (+ i 1)))
          _ (if o.calibrate? (table.insert o.files a)
                (case (a:match "^([%w%-_]+)=(.+)$")
                  (name dir) (table.insert o.scenarios {: name : dir})
                  _ (fail (.. "expected NAME=DIR, got " a)))))
        (set i (+ i 1))))
    o))

(fn calibrate [o]
  (var worst 0)
  (each [_ path (ipairs o.files)]
    (case (read-image path)
      (nil err) (fail err)
      image (let [r (states.classify image {:x1 o.x1 :y1 o.y1})]
              (set worst (math.max worst r.spread))
              (print (string.format "%s: state %.1f deg, strip spread %.2f deg%s  [%s]"
                                    path (or r.hue -1) r.spread
                                    (if (accumulate [all true _ st (ipairs r.strips)]
                                          (and all (not= nil st.hue)))
                                        ", every strip has a state" "")
                                    (strip-line r))))))
  (print (string.format "largest spread %.2f deg (tolerance %g)" worst states.tolerance)))

(fn check-scenario [o sc]
  (let [frames (list-frames sc.dir)]
    (when (= 0 (length frames)) (fail (.. sc.name ": no frames in " sc.dir)))
    (var mixed 0)
    (var worst nil)
    (var calm 0)   ; the largest strip spread of the frames judged one state
    (var lo math.huge)
    (var hi (- math.huge))
    (let [results (icollect [_ path (ipairs frames)]
                    (case (read-image path)
                      (nil err) (fail err)
                      image (let [r (states.classify image {:x1 o.x1 :y1 o.y1})]
                              (set r.path path)
                              r)))
          hues (icollect [_ r (ipairs results)] r.hue)
          first (. hues 1)
          last (. hues (length hues))
          near? (fn [a b] (and a b (<= (math.abs (- a b)) states.tolerance)))]
      (each [_ r (ipairs results)]
        (when r.hue
          (set lo (math.min lo r.hue))
          (set hi (math.max hi r.hue)))
        ;; A frame between the two states of a one-edit scenario counts as a mix.
        (when (and (. o.two-states sc.name) r.hue first last (not r.mixed?)
                   (not (near? r.hue first)) (not (near? r.hue last)))
          (set r.mixed? true)
          (set r.between? true)
          (set r.spread (math.min (math.abs (- r.hue first)) (math.abs (- r.hue last)))))
        (when (not r.mixed?) (set calm (math.max calm r.spread)))
        (when r.mixed?
          (set mixed (+ mixed 1))
          (when (or (not worst) (> r.spread worst.result.spread))
            (set worst {:path r.path :result r})))))
    (let [range (if (<= lo hi) (- hi lo) 0)
          saved (when worst
                  (let [out (.. o.out "/" sc.name "-worst.png")]
                    (os.execute (.. "mkdir -p '" o.out "'"))
                    (case (read-image worst.path)
                      (nil err) (fail err)
                      image (case (png.write-file out {:width image.width :height image.height
                                                       :pixels image.pixels :alpha? false})
                              (nil err) (fail err)
                              _ out))))]
      (print (string.format "%-10s %3d frames, %3d mixed; states seen %.0f to %.0f deg of hue (:hue %.2f to %.2f); spread within the others at most %.1f deg"
                            sc.name (length frames) mixed
                            (if (<= lo hi) lo 0) (if (<= lo hi) hi 0)
                            (states.hue->value (if (<= lo hi) lo 0))
                            (states.hue->value (if (<= lo hi) hi 0)) calm))
      (when worst
        (print (string.format "           worst %s: %s by %.0f deg (tolerance %g)\n           strip hues, top to bottom (strips of 4 rows): %s\n           saved as %s"
                              worst.path
                              (if worst.result.between?
                                  "a state between the first and the last, apart from both"
                                  "strips differ")
                              worst.result.spread states.tolerance
                              (strip-line worst.result) saved)))
      (when (< range o.min-range)
        (print (string.format "           NOT EXERCISED: the frames' states span %.1f deg, under %g: the state never changed"
                              range o.min-range)))
      {: mixed :exercised? (>= range o.min-range)})))

(fn main [argv]
  (let [o (parse-args argv)]
    (if o.calibrate?
        (calibrate o)
        (do (when (= 0 (length o.scenarios)) (fail "no NAME=DIR given"))
            (var mixed 0)
            (var unexercised 0)
            (each [_ sc (ipairs o.scenarios)]
              (let [r (check-scenario o sc)]
                (set mixed (+ mixed r.mixed))
                (when (not r.exercised?) (set unexercised (+ unexercised 1)))))
            (print (string.format "%d frames mix two states; %d scenarios not exercised"
                                  mixed unexercised))
            (os.exit (if (> unexercised 0) 2 (> mixed 0) 1 0))))))

(main [...])

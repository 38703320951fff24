;; Progressive rendering for the player: when one frame of a scene would take too long
;; (on a software renderer a heavy scene can take many seconds), the image is drawn in
;; horizontal bands, one band per frame, so input is read and the window redrawn
;; between bands and escape always works. The band count adapts to the measured frame
;; time. Pure: the caller passes the frame times in and draws the rows it is given.

(local budget 0.1)       ; seconds a frame may take before the image is split further
(local start-bands 4)    ; a new scene starts split, until its frame time is known
(local max-bands 256)

(fn new [?bands]
  "A schedule for a new picture: split into `?bands` bands (when the frame time is
known, see adaptive.render-seconds), else a few at first."
  {:bands (math.max 1 (math.min max-bands (or ?bands start-bands))) :next 1 :covered 0
   :slowest 0})

(fn bands-for [seconds]
  "The band count that keeps a frame whose whole picture takes `seconds` within the
budget."
  (math.max 1 (math.min max-bands (math.ceil (/ seconds budget)))))

(fn rows [p height]
  "The rows [y0 y1) of `height` to draw this frame."
  (let [i (math.min p.next p.bands)
        y0 (math.floor (/ (* (- i 1) height) p.bands))
        y1 (math.floor (/ (* i height) p.bands))]
    (values y0 y1)))

(fn drawn! [p]
  "Record that this frame's rows were drawn; move to the next band."
  ;; The share of the image drawn since the start, in whole passes: the bands are
  ;; drawn in order from where the last one ended, whatever their count.
  (set p.covered (+ p.covered (/ 1 p.bands)))
  (set p.next (+ (% p.next p.bands) 1)))

(fn resize! [p bands]
  (let [bands (math.max 1 (math.min max-bands bands))]
    (when (not= bands p.bands)
      ;; Go on from the same place in the image; a little is drawn twice at worst, so
      ;; the share covered counts only what lies beyond the new band's start.
      (let [at (/ (- (math.min p.next p.bands) 1) p.bands)
            next (+ 1 (math.floor (* at bands)))]
        (set p.covered (math.max 0 (- p.covered (- at (/ (- next 1) bands)))))
        (set p.next next)
        (set p.bands bands)))))

(fn measured! [p seconds]
  "Feed the duration of the last frame: more bands when it was over the budget (in
proportion, so one slow frame is enough), fewer when far under it."
  (set p.slowest (math.max p.slowest seconds))
  (if (and (> seconds budget) (< p.bands max-bands))
      (resize! p (* p.bands (math.min 16 (math.ceil (/ seconds budget)))))
      (and (< seconds (/ budget 4)) (> p.bands 1))
      (resize! p (math.floor (/ p.bands 2)))))

(fn complete? [p]
  "True once every row of the image has been drawn at least once."
  (>= p.covered (- 1 1e-9)))

{: new : bands-for : rows : drawn! : measured! : complete? : budget : max-bands}

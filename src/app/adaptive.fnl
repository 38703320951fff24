;; Adaptive resolution for the player. While the scene's state changes (the camera
;; moves, a slider is dragged, the clock of an animated scene runs) every frame is a
;; whole picture at a lower scale, chosen to hold a target frame time; when the state
;; stays, the full resolution is refined over the next frames (src/app/progress.fnl).
;;
;; The scale comes from a model of frame time measured as it goes: a frame costs the
;; scene's render, c + b * pixels for its shader (a line fitted to the last renders of
;; that shader, timed to the end of the renderer's work), plus what the frame spends on
;; everything else (the HUD, the window's present, Lua), which no scale changes. When
;; that alone is over the target, the target is out of reach and the HUD says so.
;; Pure: the caller passes the timings in.

(local min-scale 0.05)
;; A shader with no render measured yet: the scale of its first picture when the
;; caller has not measured one small render first (see the player's probe!): 1/8 of
;; the window's width and height.
(local first-scale 0.125)
;; How much each new render counts in the fitted line (older ones fade by 1 - this).
(local weight 0.3)

(fn camera-key [cam]
  (string.format "%.9g %.9g %.9g %.9g %.9g %.9g" (. cam.pos 1) (. cam.pos 2) (. cam.pos 3)
                 cam.yaw cam.pitch cam.fov))

(fn new []
  "A model with nothing measured yet."
  {:fixed nil :shaders {} :out-of-reach? false})

(fn fade-in [s x y]
  ;; Exponentially weighted sums for the least-squares line y = c + b x.
  (let [k (- 1 weight)]
    (set s.n (+ (* k s.n) weight))
    (set s.x (+ (* k s.x) (* weight x)))
    (set s.y (+ (* k s.y) (* weight y)))
    (set s.xx (+ (* k s.xx) (* weight x x)))
    (set s.xy (+ (* k s.xy) (* weight x y)))))

(fn line-of [s]
  "The fitted (c, b) of a shader's render time against its pixel count: the weighted
least-squares line when the pixel counts measured differ enough to tell a slope from
an offset, else the line through the origin (all of the time in proportion)."
  (let [mx (/ s.x s.n) my (/ s.y s.n)
        vx (- (/ s.xx s.n) (* mx mx))
        cxy (- (/ s.xy s.n) (* mx my))]
    (if (> vx (* 0.01 mx mx))
        (let [b (/ cxy vx)
              c (- my (* b mx))]
          (if (and (> b 0) (>= c 0)) (values c b)
              (values 0 (/ s.xy s.xx))))
        (values 0 (/ s.xy s.xx)))))

(fn rendered! [a shader pixels seconds]
  "Feed one render of `pixels` with `shader` (a key) that took `seconds` (to the end
of the renderer's work)."
  (let [s (or (. a.shaders shader)
              (let [s {:n 0 :x 0 :y 0 :xx 0 :xy 0}] (tset a.shaders shader s) s))]
    (fade-in s (math.max 1 pixels) seconds)))

(fn measured! [a shader pixels render-seconds frame-seconds]
  "Feed one frame that rendered `pixels` with `shader` (a key): the render took
`render-seconds` (to the end of the renderer's work), the whole frame `frame-seconds`."
  (rendered! a shader pixels render-seconds)
  (let [other (math.max 0 (- frame-seconds render-seconds))]
    (set a.fixed (if a.fixed (+ (* (- 1 weight) a.fixed) (* weight other)) other))))

(fn known? [a shader]
  "True once a render of `shader` has been measured."
  (not= nil (. a.shaders shader)))

(fn render-seconds [a shader pixels]
  "The predicted render time of `pixels` with `shader`, or nil before any is measured."
  (case (. a.shaders shader)
    s (let [(c b) (line-of s)] (+ c (* b pixels)))))

(fn scale-for [a shader target window-pixels max-scale]
  "The scale (of the window's width and height) for a whole picture with `shader`
that meets `target` seconds a frame, within [0.05, max-scale]; 1/8 for a shader not
measured yet. Sets a.out-of-reach? when even the smallest picture cannot meet it."
  (case (. a.shaders shader)
    nil (math.min first-scale max-scale)
    s (let [(c b) (line-of s)
            room (- target (or a.fixed 0) c)
            ideal (if (> room 0) (math.sqrt (/ (/ room b) window-pixels)) 0)]
        (set a.out-of-reach? (< ideal min-scale))
        (math.max min-scale (math.min max-scale ideal)))))

{: new : camera-key : rendered! : measured! : known? : render-seconds : scale-for : min-scale : first-scale}

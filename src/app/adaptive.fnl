;; Adaptive resolution for the player: while the camera moves, the image is rendered
;; at a lower scale chosen to hold a target frame time (frame time grows with the
;; pixel count, the square of the scale); when the camera stops, the full-resolution
;; image is refined over the next frames (progressive bands, src/app/progress.fnl).
;; Pure: the caller passes the camera and the frame times in.

(local min-scale 0.05)

(fn camera-key [cam]
  (string.format "%.9g %.9g %.9g %.9g %.9g %.9g" (. cam.pos 1) (. cam.pos 2) (. cam.pos 3)
                 cam.yaw cam.pitch cam.fov))

(fn new [scale]
  "State for a player whose chosen render scale is `scale`."
  {:moving? false :scale (math.max min-scale (* 0.5 scale)) :last-key nil :stopped-at nil})

(fn next-scale [scale seconds target max-scale]
  "The moving scale for the next frame, from this frame's `seconds` at `scale`: the
scale whose pixel count meets `target` seconds, approached half-way (so one odd frame
does not make the image jump), within [0.05, max-scale]."
  (let [ideal (* scale (math.sqrt (/ target (math.max seconds 1e-4))))]
    (math.max min-scale (math.min max-scale (* 0.5 (+ scale ideal))))))

(fn update! [a cam seconds target max-scale]
  "Feed this frame's camera and frame time. Returns :moving, :stopped (the frame the
camera came to rest) or :still."
  (let [key (camera-key cam)
        moved? (and a.last-key (not= key a.last-key))
        was-moving? a.moving?]
    (set a.last-key key)
    (if moved?
        (do (when was-moving? (set a.scale (next-scale a.scale seconds target max-scale)))
            (set a.scale (math.min a.scale max-scale))
            (set a.moving? true)
            :moving)
        was-moving? (do (set a.moving? false) :stopped)
        :still)))

{: new : update! : next-scale}

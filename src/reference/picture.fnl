;; Whole pictures from the CPU reference, small ones first: what the player shows of a
;; new scene while its shader compiles (src/app/preview.fnl runs this in a thread).
;; A picture is one ray through each pixel's centre (the draft, the player's moving
;; picture), as RGBA bytes, rows from the top. Pure: runs under plain LuaJIT.

(local reference (require :src.reference))
(local camera (require :src.render.camera))

;; The ladder's rungs: picture heights, each twice the last, while their pixels stay
;; within the largest a preview draws (see ladder).
(local first-height 9)

(fn ladder [aspect max-pixels]
  "The sizes, [w h] smallest first, of the pictures a preview draws for a window of
`aspect` (width / height): heights 9, 18, 36, 72... (each width the height times the
aspect, rounded, at least 1) while a picture holds at most `max-pixels` pixels; the
first one always."
  (let [sizes []]
    (var h first-height)
    (while (let [w (math.max 1 (math.floor (+ 0.5 (* h aspect))))]
             (when (or (= 0 (length sizes)) (<= (* w h) max-pixels))
               (table.insert sizes [w h])
               true))
      (set h (* 2 h)))
    sizes))

(fn byte-of [c]
  ;; A channel in 0..1 (the tracer clamps it) as the byte a GPU target stores.
  (math.floor (+ 0.5 (* 255 (math.max 0 (math.min 1 c))))))

(fn picture [scene plan cam width height ?stop?]
  "The `width` x `height` picture of `scene` lowered to `plan` seen by `cam`: one ray
through each pixel's centre, traced by the CPU reference, as a string of RGBA bytes
(rows from the top, alpha 255). `?stop?` (fn [] true to stop) is asked before each
row: nil when it said stop."
  (let [T (reference.tracer scene plan
                            {:cam-pos cam.pos
                             :pixel-angle (/ 1 (* (camera.projection-distance cam) height))})
        ray (reference.ray-setup cam width height)
        [ox oy oz] cam.pos
        rows []]
    (var stopped? false)
    (for [y 0 (- height 1) &until stopped?]
      (if (and ?stop? (?stop?))
          (set stopped? true)
          (let [row []]
            (for [x 0 (- width 1)]
              (let [[r g b] (. (T.trace ox oy oz (ray x y)) :color)]
                (table.insert row (string.char (byte-of r) (byte-of g) (byte-of b) 255))))
            (table.insert rows (table.concat row)))))
    (when (not stopped?) (table.concat rows))))

{: ladder : picture : first-height}

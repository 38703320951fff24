;; Image comparison helpers for checking GPU renders against the CPU reference: pixel
;; differences, their statistics, and the choice of pixels worth comparing (a jittered
;; grid plus pixels at silhouettes, shadow edges and reflected edges). Pure Lua data.

(local reference (require :src.reference))

(local abs math.abs)
(local floor math.floor)

(fn pixel-diff [[ar ag ab] [br bg bb]]
  "Largest channel difference between two colours given in the same units (the
GPU's 0..255 against the reference colour * 255)."
  (math.max (abs (- ar br)) (abs (- ag bg)) (abs (- ab bb))))

(fn fuzzy-equal? [a b tolerance]
  "Whether colours a and b differ by at most `tolerance` in every channel."
  (<= (pixel-diff a b) tolerance))

(fn stats [diffs threshold]
  "Statistics of a list of differences: {:max :mean :over (how many are above
`threshold`) :count}."
  (var sum 0)
  (var biggest 0)
  (var over 0)
  (each [_ d (ipairs diffs)]
    (set sum (+ sum d))
    (when (> d biggest) (set biggest d))
    (when (> d threshold) (set over (+ over 1))))
  (let [n (length diffs)]
    {:max biggest :mean (if (> n 0) (/ sum n) 0) : over :count n}))

;;; Deterministic pseudo-random numbers: Park and Miller's minimal standard generator,
;;; exact in doubles, so the chosen pixels never depend on math.random's state.

(fn rng [seed]
  (var state (let [s (% (floor (or seed 1)) 2147483647)] (if (<= s 0) 1 s)))
  (fn []
    (set state (% (* state 16807) 2147483647))
    (/ state 2147483647)))

(fn signature [result]
  "What makes a pixel's shading discrete: the objects its primary ray and its bounces
hit, and whether the primary hit is in shadow."
  (.. (table.concat result.path ",") (if result.shadowed? "s" "")))

(fn grid-pixels [width height n random]
  "One pixel per cell of an n x n grid over the image, jittered within its cell."
  (let [out []]
    (for [j 0 (- n 1)]
      (for [i 0 (- n 1)]
        (let [x0 (floor (/ (* i width) n)) x1 (floor (/ (* (+ i 1) width) n))
              y0 (floor (/ (* j height) n)) y1 (floor (/ (* (+ j 1) height) n))
              x (math.min (- width 1) (+ x0 (floor (* (random) (math.max 1 (- x1 x0))))))
              y (math.min (- height 1) (+ y0 (floor (* (random) (math.max 1 (- y1 y0))))))]
          (table.insert out [x y]))))
    out))

(fn edge-pixels [scene plan cam width height step]
  "Pixels on either side of a change of signature (silhouette, shadow edge or an edge
seen in a reflection), found on a coarse grid of `step` pixels and refined by
bisection between neighbouring coarse samples. A list of [x y], in scan order."
  (let [T (reference.tracer scene plan)
        ray (reference.ray-setup cam width height)
        [ox oy oz] cam.pos
        cache {}
        sig (fn [x y]
              (let [key (+ x (* y width))]
                (when (= nil (. cache key))
                  (let [(dx dy dz) (ray x y)]
                    (tset cache key (signature (T.trace ox oy oz dx dy dz)))))
                (. cache key)))
        xs (fcollect [x 0 (- width 1) step] x)
        ys (fcollect [y 0 (- height 1) step] y)
        found {}
        out []
        add (fn [x y]
              (let [key (+ x (* y width))]
                (when (not (. found key))
                  (tset found key true)
                  (table.insert out [x y]))))
        ;; Bisect the segment a..b (along x when horizontal?, else along y) whose ends
        ;; differ, down to two neighbouring pixels, and add both.
        refine (fn [horizontal? fixed a b]
                 (var (lo hi) (values a b))
                 (let [at (fn [v] (if horizontal? (sig v fixed) (sig fixed v)))
                       s-lo (at lo)]
                   (while (> (- hi lo) 1)
                     (let [mid (floor (/ (+ lo hi) 2))]
                       (if (= (at mid) s-lo) (set lo mid) (set hi mid))))
                   (if horizontal?
                       (do (add lo fixed) (add hi fixed))
                       (do (add fixed lo) (add fixed hi)))))]
    (each [yi y (ipairs ys)]
      (each [xi x (ipairs xs)]
        (let [here (sig x y)
              right (. xs (+ xi 1))
              below (. ys (+ yi 1))]
          (when (and right (not= here (sig right y))) (refine true y x right))
          (when (and below (not= here (sig x below))) (refine false x y below)))))
    out))

(fn sample-pixels [scene plan cam width height ?options]
  "Pixels of a width x height image worth comparing, as a list of [x y] (0-based, each
also tagged :kind :grid or :edge), without repeats. Options:
  :grid n   one jittered pixel in each cell of an n x n grid (default 16)
  :extra m  up to m pixels beside silhouettes, shadow edges and reflected edges, found
            by a coarse reference pass (default 256), chosen evenly when there are more
  :step k   spacing of the coarse pass in pixels (default 4)
  :seed s   seed of the jitter and of the choice of edge pixels (default 1)
The result is deterministic and has at least n*n pixels."
  (let [options (or ?options {})
        n (or options.grid 16)
        extra (or options.extra 256)
        step (or options.step 4)
        random (rng (or options.seed 1))
        taken {}
        out []
        add (fn [[x y] kind]
              (let [key (+ x (* y width))]
                (when (not (. taken key))
                  (tset taken key true)
                  (table.insert out {1 x 2 y : kind}))))]
    (each [_ p (ipairs (grid-pixels width height n random))] (add p :grid))
    (let [edges (edge-pixels scene plan cam width height step)]
      ;; A seeded shuffle, then the first `extra`: spread over all the edges found.
      (for [i (length edges) 2 -1]
        (let [j (+ 1 (floor (* (random) i)))
              swap (. edges i)]
          (tset edges i (. edges j))
          (tset edges j swap)))
      (var added 0)
      (each [_ p (ipairs edges) &until (>= added extra)]
        (when (not (. taken (+ (. p 1) (* (. p 2) width))))
          (add p :edge)
          (set added (+ added 1)))))
    out))

{: pixel-diff : fuzzy-equal? : stats : sample-pixels : signature}

;; Checks of distance fields that need no second formula, shared by the primitive and
;; operation specs: numerical gradients, a dense sample of a surface, random points
;; outside a shape.

;; A deterministic generator, so a failure names a point that can be found again.
(fn lcg [seed]
  (var s seed)
  (fn []
    (set s (% (+ (* s 1103515245) 12345) 2147483648))
    (/ s 2147483648)))

(fn gradient [f x y z h]
  (values (/ (- (f (+ x h) y z) (f (- x h) y z)) (* 2 h))
          (/ (- (f x (+ y h) z) (f x (- y h) z)) (* 2 h))
          (/ (- (f x y (+ z h)) (f x y (- z h))) (* 2 h))))

(fn surface-samples [f [hx hy hz] n]
  "Points on the surface: sign changes along the edges of an n^3 grid over the box
(1.25 times the bounds), refined by bisection. Returns the points and the grid spacing."
  (let [sx (* hx 1.25) sy (* hy 1.25) sz (* hz 1.25)
        step-x (/ (* 2 sx) n) step-y (/ (* 2 sy) n) step-z (/ (* 2 sz) n)
        pts []]
    (fn bisect [ax ay az bx by bz fa]
      (var (lx ly lz lf) (values ax ay az fa))
      (var (ux uy uz) (values bx by bz))
      (for [_ 1 40]
        (let [mx (* 0.5 (+ lx ux)) my (* 0.5 (+ ly uy)) mz (* 0.5 (+ lz uz))
              fm (f mx my mz)]
          (if (= (< fm 0) (< lf 0))
              (set (lx ly lz lf) (values mx my mz fm))
              (set (ux uy uz) (values mx my mz)))))
      (table.insert pts [(* 0.5 (+ lx ux)) (* 0.5 (+ ly uy)) (* 0.5 (+ lz uz))]))
    (for [i 0 n]
      (for [j 0 n]
        (for [k 0 n]
          (let [x (+ (- sx) (* i step-x)) y (+ (- sy) (* j step-y)) z (+ (- sz) (* k step-z))
                v (f x y z)]
            (when (< i n)
              (let [x2 (+ x step-x) v2 (f x2 y z)]
                (when (not= (< v 0) (< v2 0)) (bisect x y z x2 y z v))))
            (when (< j n)
              (let [y2 (+ y step-y) v2 (f x y2 z)]
                (when (not= (< v 0) (< v2 0)) (bisect x y z x y2 z v))))
            (when (< k n)
              (let [z2 (+ z step-z) v2 (f x y z2)]
                (when (not= (< v 0) (< v2 0)) (bisect x y z x y z2 v))))))))
    (values pts (math.max step-x step-y step-z))))

(fn nearest [pts x y z]
  (var best math.huge)
  (each [_ [px py pz] (ipairs pts)]
    (let [dx (- x px) dy (- y py) dz (- z pz)
          d2 (+ (* dx dx) (* dy dy) (* dz dz))]
      (when (< d2 best) (set best d2))))
  (math.sqrt best))

(fn outside-points [f [hx hy hz] count seed]
  ;; Random points in twice the bounds, at least 0.05 outside the surface.
  (let [rand (lcg seed)
        out []]
    (for [_ 1 (* count 20) &until (>= (length out) count)]
      (let [x (* hx 2 (- (* 2 (rand)) 1)) y (* hy 2 (- (* 2 (rand)) 1))
            z (* hz 2 (- (* 2 (rand)) 1))]
        (when (> (f x y z) 0.05) (table.insert out [x y z]))))
    out))

{: lcg : gradient : surface-samples : nearest : outside-points}

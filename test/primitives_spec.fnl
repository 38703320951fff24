;; tier: fast
;; Every primitive descriptor (src/sdf/primitives/*.fnl), with its default parameters,
;; against properties that need no second formula:
;; - exact ones: at random points outside, |gradient| = 1 and p - d * gradient lands
;;   on the surface, and d agrees with the distance to a dense sample of the surface;
;; - bounds: never above the distance to that dense sample (less its spacing).
;; The analytic oracles of the original kinds are in test/oracles_spec.fnl.

(local primitives (require :src.sdf.primitives))

(fn defaults-of [d]
  (collect [_ p (ipairs d.params)] p.name p.default))

(fn field [d ?o]
  (let [args ((. d :pack) (or ?o (defaults-of d)))
        cpu d.cpu]
    (fn [x y z] (cpu x y z (unpack args)))))

(local {: gradient : surface-samples : nearest : outside-points}
  (require :test.support.fields))

(fn extent [d]
  ;; Sampling box half extents: the shape's bounds, or a box of 2 for unbounded ones.
  (let [b (and d.bounds (d.bounds (defaults-of d)))]
    (if b b [2 2 2])))

(describe "primitive catalogue"
  (fn []
    (it "has at least 25 primitives, each with valid defaults"
      (fn []
        (assert.is_true (>= (length primitives.all) 25)
                        (.. "only " (length primitives.all) " primitives"))
        (each [_ d (ipairs primitives.all)]
          (when d.check
            (let [(bad why) (d.check (defaults-of d))]
              (assert.is_nil bad (.. d.kind ": defaults fail their own check: "
                                     (tostring bad) " " (tostring why))))))))
    (it "packs as many numbers as its GLSL arguments take"
      (fn []
        (each [_ d (ipairs primitives.all)]
          (assert.are.equal d.arg-size (length (d.pack (defaults-of d))) d.kind))))
    ;; Issue 30: no hand-written GLSL; the translator writes :glsl and :cpu from one
    ;; form, so the GPU and the CPU reference cannot say different things.
    (it "is written once in Fennel, with the forms it lowers to instead"
      (fn []
        (each [_ d (ipairs primitives.all)]
          (assert.is_string d.fennel d.kind)
          (each [_ v (ipairs (or d.variants []))]
            (assert.is_string v.fennel (.. d.kind "'s variant " v.kind))
            (assert.truthy (v.glsl:find (.. "float " v.glsl-name "(vec3 p") 1 true) v.kind)
            (assert.is_function v.cpu v.kind)))))
    (it "gives a flat plane's distance through its ground form"
      (fn []
        (let [plane (primitives.lookup :plane)
              o {:normal [0 0 1] :height 0.75}
              ground (plane.variant o)
              a (plane.pack o)
              b (ground.pack o)]
          (assert.are.equal :ground ground.kind)
          (each [_ [x y z] (ipairs [[0 0 0] [1 -2 3] [-4 5 -0.5] [0.25 0.5 0.75]])]
            (assert.are.equal (plane.cpu x y z (unpack a)) (ground.cpu x y z (unpack b)))))))))

(describe "exact primitives"
  (fn []
    (each [_ d (ipairs primitives.all)]
      (when (= d.class :exact)
        (it (.. d.kind ": |gradient| = 1 and p - d * gradient is on the surface, outside")
          (fn []
            (let [f (field d)
                  pts (outside-points f (extent d) 300 7)]
              (var checked 0)
              (assert.is_true (>= (length pts) 100) (.. d.kind ": too few points outside"))
              (each [_ [x y z] (ipairs pts)]
                ;; Central differences with h = 1e-5 have an error of order h^2 times
                ;; the curvature, and rounding of order 1e-16 / h: 1e-4 covers both.
                ;; Points whose gradient changes between h and 4h straddle a kink
                ;; (the medial axis), where no gradient exists: skipped.
                (let [(gx gy gz) (gradient f x y z 1e-5)
                      (ax ay az) (gradient f x y z 4e-5)]
                  (when (< (+ (math.abs (- gx ax)) (math.abs (- gy ay)) (math.abs (- gz az))) 1e-4)
                    (set checked (+ checked 1))
                    (let [g (math.sqrt (+ (* gx gx) (* gy gy) (* gz gz)))
                          v (f x y z)
                          on (f (- x (* v gx)) (- y (* v gy)) (- z (* v gz)))]
                      (assert.is_true (< (math.abs (- g 1)) 1e-4)
                                      (string.format "%s at (%g %g %g): |gradient| = %.6f"
                                                     d.kind x y z g))
                      ;; The projection's error is of the gradient's error times d.
                      (assert.is_true (< (math.abs on) (* 1e-4 (+ 1 v)))
                                      (string.format "%s at (%g %g %g): d = %g, projection lands at %g"
                                                     d.kind x y z v on))))))
              ;; Most points have a gradient; if not, the test proves nothing.
              (assert.is_true (> checked (* 0.8 (length pts)))
                              (.. d.kind ": only " checked " of " (length pts) " points checked")))))))))

(describe "exact normals in closed form"
  (fn []
    (it "come with sphere, box and plane"
      (fn []
        (each [_ kind (ipairs [:sphere :box :plane])]
          (assert.is_function (. (primitives.lookup kind) :gradient) kind))))
    (each [_ d (ipairs primitives.all)]
      (when d.gradient
        (it (.. d.kind ": the closed-form normal is the distance's gradient, inside and out")
          (fn []
            (let [f (field d)
                  args (d.pack (defaults-of d))
                  [ex ey ez] (extent d)]
              (var seed 11)
              (fn rnd [] (set seed (% (+ (* seed 1103515245) 12345) 2147483648)) (/ seed 2147483648))
              (var checked 0)
              (for [_ 1 400]
                (let [x (* 2 ex (- (* 2 (rnd)) 1)) y (* 2 ey (- (* 2 (rnd)) 1)) z (* 2 ez (- (* 2 (rnd)) 1))
                      (gx gy gz) (gradient f x y z 1e-5)
                      (ax ay az) (gradient f x y z 4e-5)]
                  ;; Away from kinks (as above), the differences are the gradient.
                  (when (< (+ (math.abs (- gx ax)) (math.abs (- gy ay)) (math.abs (- gz az))) 1e-4)
                    (set checked (+ checked 1))
                    (let [(nx ny nz) (d.gradient x y z (unpack args))]
                      (assert.is_true (< (+ (math.abs (- nx gx)) (math.abs (- ny gy)) (math.abs (- nz gz))) 1e-4)
                                      (string.format "%s at (%g %g %g): closed form (%g %g %g), differences (%g %g %g)"
                                                     d.kind x y z nx ny nz gx gy gz))))))
              (assert.is_true (> checked 300) (.. d.kind ": only " checked " points checked")))))))))

(describe "distance against a dense sample of the surface"
  (fn []
    (each [_ d (ipairs primitives.all)]
      (when d.bounds
        (it (.. d.kind ": " (if (= d.class :exact) "equals" "never exceeds")
                " the distance to the sampled surface")
          (fn []
            (let [f (field d)
                  box (extent d)
                  (surface spacing) (surface-samples f box 36)
                  pts (outside-points f box 60 11)]
              (assert.is_true (> (length surface) 100) (.. d.kind ": no surface found"))
              (each [_ [x y z] (ipairs pts)]
                (let [v (f x y z)
                      est (nearest surface x y z)]
                  ;; The sampled surface has gaps up to the grid spacing, so the
                  ;; estimate exceeds the true distance by at most about that.
                  (assert.is_true (<= v (+ est (* 0.01 spacing)))
                                  (string.format "%s at (%g %g %g): d = %g is above the distance %g to the surface"
                                                 d.kind x y z v est))
                  (when (= d.class :exact)
                    (assert.is_true (>= v (- est spacing))
                                    (string.format "%s at (%g %g %g): d = %g is far below the distance %g"
                                                   d.kind x y z v est))))))))))))

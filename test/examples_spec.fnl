;; tier: fast
;; The example scenes of examples/ written as a Shadertoy author writes them (issue 44):
;; a Mandelbulb (&until on escape), a Mandelbox (folds by clamp), a gyroid shell,
;; repeated pillars (mod), a smooth blend (smin as a helper), a cairn of IQ's
;; ellipsoids (arrays of the file), a twisted column and a bent bar (a rotation
;; helper giving a vector), a chain of links.
;; Each loads through the app's loader, and each custom node's translated Lua gives
;; what an independent implementation written here in plain scalar math gives; the
;; Mandelbulb draws whole with the default step budget (no CPU reference ray runs out
;; of steps). test/examples_gpu_spec.fnl checks the GPU side.
(local load (require :src.scene.load))
(local custom (require :src.sdf.custom))
(local plan-mod (require :src.render.plan))
(local camera (require :src.render.camera))
(local reference (require :src.reference))
(local {: lcg} (require :test.support.fields))

(local unpack (or table.unpack _G.unpack))

;;; The independent implementations: scalar math, one coordinate at a time.

(fn clamp [x lo hi] (math.min (math.max x lo) hi))
(fn len2 [x y] (math.sqrt (+ (* x x) (* y y))))
(fn len3 [x y z] (math.sqrt (+ (* x x) (* y y) (* z z))))
(fn fmod [x y] (- x (* y (math.floor (/ x y)))))

(fn box [x y z bx by bz]
  (let [qx (- (math.abs x) bx) qy (- (math.abs y) by) qz (- (math.abs z) bz)]
    (+ (len3 (math.max qx 0) (math.max qy 0) (math.max qz 0))
       (math.min (math.max qx qy qz) 0))))

(fn round-box [x y z bx by bz r]
  ;; IQ's rounded box: the box shrunk by r, then r off its distance.
  (- (box x y z (- bx r) (- by r) (- bz r)) r))

(fn mandelbulb [x y z]
  ;; Power 8 in spherical coordinates (theta from the z axis), 8 turns at most, out
  ;; once |z| > 2; r kept off 0 as the scene does (the origin's orbit stays there).
  ;; z^8 is written as 8 products, as the translator writes (^ r 8): LuaJIT's pow
  ;; rounds differently, and the orbit of a point inside the bulb, which never
  ;; escapes, multiplies a last-bit difference by up to 8 r^7 per turn.
  (var (zx zy zz) (values x y z))
  (var dr 1)
  (var r (math.max (len3 x y z) 1e-9))
  (var i 1)
  (while (and (<= i 8) (<= r 2))
    (let [theta (* 8 (math.atan2 (len2 zx zy) zz))
          phi (* 8 (math.atan2 zy zx))
          r7 (* r r r r r r r)
          r8 (* r7 r)]
      (set dr (+ (* 8 r7 dr) 1))
      (set zx (+ (* r8 (math.sin theta) (math.cos phi)) x))
      (set zy (+ (* r8 (math.sin theta) (math.sin phi)) y))
      (set zz (+ (* r8 (math.cos theta)) z))
      (set r (math.max (len3 zx zy zz) 1e-9)))
    (set i (+ i 1)))
  (* 0.5 (math.log r) (/ r dr)))

(fn mandelbox [x y z scale]
  ;; Ten turns of a box fold (each component reflected past -1 and 1), a sphere fold
  ;; (times 4 inside radius 0.5, inverted between 0.5 and 1), the scale, plus the
  ;; point; the estimate |z| / |dr|.
  (var (zx zy zz) (values x y z))
  (var dr 1)
  (for [_ 1 10]
    (let [fold #(- (* 2 (clamp $ -1 1)) $)
          fx (fold zx) fy (fold zy) fz (fold zz)
          r2 (+ (* fx fx) (* fy fy) (* fz fz))
          k (if (< r2 0.25) 4 (< r2 1) (/ 1 r2) 1)]
      (set zx (+ (* fx k scale) x))
      (set zy (+ (* fy k scale) y))
      (set zz (+ (* fz k scale) z))
      (set dr (+ (* dr k (math.abs scale)) 1))))
  (/ (len3 zx zy zz) (math.abs dr)))

(fn gyroid-shell [x y z scale thickness]
  (let [sx (* x scale) sy (* y scale) sz (* z scale)
        g (+ (* (math.sin sx) (math.cos sy)) (* (math.sin sy) (math.cos sz))
             (* (math.sin sz) (math.cos sx)))]
    (math.max (- (math.abs (/ g scale)) thickness)
              (round-box x y z 1.1 1.1 1.1 0.15))))

(fn cylinder [x y z r h]
  ;; A capped cylinder along z: radius r, half height h.
  (let [dr (- (len2 x y) r) dz (- (math.abs z) h)]
    (+ (math.min (math.max dr dz) 0) (len2 (math.max dr 0) (math.max dz 0)))))

(fn pillar-grid [x y z spacing]
  (let [half (* 0.5 spacing)
        cx (- (fmod (+ x half) spacing) half)
        cy (- (fmod (+ y half) spacing) half)
        pillar (math.min (cylinder cx cy z 0.16 1)
                         (box cx cy (+ z 0.95) 0.24 0.24 0.07)
                         (box cx cy (- z 0.95) 0.22 0.22 0.06))]
    (math.max pillar (box x y z 4.2 3 1.02))))

(fn smin [a b k]
  (let [h (math.max (- k (math.abs (- a b))) 0)]
    (- (math.min a b) (/ (* h h 0.25) k))))

(fn smooth-blend [x y z k]
  (let [ball (- (len3 x y (- z 0.35)) 0.55)
        torus (- (len2 (- (len2 x y) 0.9) (+ z 0.3)) 0.2)
        cube (box (- x 0.95) (- y 0.6) (+ z 0.45) 0.3 0.3 0.3)
        ;; The capsule from a (-1.1 0.5 -0.5) to b (-0.6 -0.3 0.7), radius 0.17.
        pax (+ x 1.1) pay (- y 0.5) paz (+ z 0.5)
        bax 0.5 bay -0.8 baz 1.2
        h (clamp (/ (+ (* pax bax) (* pay bay) (* paz baz)) (+ (* bax bax) (* bay bay) (* baz baz))) 0 1)
        capsule (- (len3 (- pax (* bax h)) (- pay (* bay h)) (- paz (* baz h))) 0.17)]
    (smin (smin (smin ball torus k) cube k) capsule k)))

(local stones [[0 0 0.26 0.78 0.6 0.27] [0.08 -0.04 0.68 0.58 0.44 0.2]
               [-0.05 0.05 1.0 0.42 0.34 0.15] [0.03 0 1.26 0.3 0.24 0.12]
               [0 0.02 1.45 0.16 0.14 0.08]])

(fn pebble-cairn [x y z]
  ;; The nearest of the stones by IQ's ellipsoid bound k0 (k0 - 1) / k1.
  (accumulate [d math.huge _ [cx cy cz rx ry rz] (ipairs stones)]
    (let [px (- x cx) py (- y cy) pz (- z cz)
          k0 (len3 (/ px rx) (/ py ry) (/ pz rz))
          k1 (len3 (/ px (* rx rx)) (/ py (* ry ry)) (/ pz (* rz rz)))]
      (math.min d (/ (* k0 (- k0 1)) k1)))))

(fn twisted-column [x y z twist]
  (let [a (* twist z) c (math.cos a) s (math.sin a)]
    (round-box (- (* c x) (* s y)) (+ (* s x) (* c y)) z 0.4 0.4 1.3 0.06)))

(fn bent-bar [x y z bend]
  (let [a (* bend x) c (math.cos a) s (math.sin a)]
    (round-box (- (* c x) (* s z)) y (+ (* s x) (* c z)) 1 0.25 0.25 0.08)))

(fn chain-links [x y z pitch]
  ;; Four of IQ's links, centres at y = pitch (i - 2.5); the even ones turned a
  ;; quarter about y (x and z swapped).
  (var d math.huge)
  (for [i 1 4]
    (let [qy (- y (* pitch (- i 2.5)))
          (qx qz) (if (= (% i 2) 0) (values z x) (values x z))
          ly (math.max (- (math.abs qy) 0.25) 0)]
      (set d (math.min d (- (len2 (- (len2 qx ly) 0.32) qz) 0.1)))))
  d)

;; Each example: its custom nodes' independent implementations, in the order of the
;; scene's objects, with their parameters as in the file.
(local examples
  [{:file "examples/mandelbulb.fnl" :nodes [mandelbulb]}
   {:file "examples/mandelbox.fnl" :nodes [#(mandelbox $1 $2 $3 -2.5)]}
   {:file "examples/gyroid-shell.fnl" :nodes [#(gyroid-shell $1 $2 $3 5 0.04)]}
   {:file "examples/pillar-grid.fnl" :nodes [#(pillar-grid $1 $2 $3 1.2)]}
   {:file "examples/smooth-blend.fnl" :nodes [#(smooth-blend $1 $2 $3 0.35)]}
   {:file "examples/pebble-cairn.fnl" :nodes [pebble-cairn]}
   {:file "examples/twisted-box.fnl" :nodes [#(twisted-column $1 $2 $3 1.4) #(bent-bar $1 $2 $3 0.5)]}
   {:file "examples/chain-links.fnl" :nodes [#(chain-links $1 $2 $3 0.9)]}])

(local points-per-node 400)

(fn custom-nodes [scene]
  (icollect [_ o (ipairs scene.objects)] (when (?. o :tree :custom) o.tree)))

(fn march-all [file]
  "The primary ray of every pixel of a 64 x 48 picture of `file` through the CPU
reference: the size, the rays that ran out of steps (the whole budget taken: no
surface within it, so the shader draws what lies past the shape's bounds, the floor
or the sky, a hole in the shape), the rays that hit objects[2], the budget and the
most steps a ray took."
  (let [scene (assert (load.load-file file))
        p (assert (plan-mod.scene->plan scene {:view :heat}))
        cam (camera.from-scene scene)
        [w h] [64 48]
        pixels (let [out []]
                 (for [y 0 (- h 1)] (for [x 0 (- w 1)] (table.insert out [x y])))
                 out)
        results (reference.render-pixels scene p cam w h pixels)
        max-steps scene.render.max-steps]
    {: w : h : max-steps
     :out-of-steps (icollect [_ r (ipairs results)]
                     (when (>= r.steps max-steps) r))
     :on-bulb (accumulate [n 0 _ r (ipairs results)] (if (= r.object 2) (+ n 1) n))
     :most (accumulate [m 0 _ r (ipairs results)] (math.max m r.steps))}))

(describe "the example scenes of examples/, written as on Shadertoy"
  (fn []
    (each [_ {: file : nodes} (ipairs examples)]
      (it (.. file ": loads, each custom node's Lua giving what the scalar implementation gives at "
              points-per-node " points")
        (fn []
          (let [scene (assert (load.load-file file))
                found (custom-nodes scene)
                rand (lcg 44)]
            (assert.are.equal (length nodes) (length found))
            (each [k node (ipairs found)]
              (let [desc (custom.descriptor node)
                    args (desc.pack node)
                    ;; The loader's function multiplies by 1 / its factor (the last
                    ;; argument): the implementation's value is scaled alike.
                    scale (. args (length args))
                    [hx hy hz] node.bounds]
                (var worst 0)
                (for [_ 1 points-per-node]
                  ;; The bounds grown by half: inside, near and outside the shape.
                  (let [x (* 1.5 hx (- (* 2 (rand)) 1))
                        y (* 1.5 hy (- (* 2 (rand)) 1))
                        z (* 1.5 hz (- (* 2 (rand)) 1))
                        want (* scale ((. nodes k) x y z))
                        got (desc.cpu x y z (unpack args))
                        err (/ (math.abs (- got want)) (+ 1 (math.abs want)))]
                    (set worst (math.max worst err))
                    ;; Both are double arithmetic of the same formulas, but the
                    ;; grouping differs (a sum of squares, a product of a scale, the
                    ;; rotation's terms), so they may differ by a few roundings of
                    ;; 1e-16 of the values the formula passes through, which are of
                    ;; order 1 near the surface (a length less a radius), hence
                    ;; relative to 1 + |want|. 1e-8 is ten million such roundings
                    ;; (room for the Mandelbulb's orbit, which multiplies a rounding
                    ;; by up to 8 r^7 a turn) and far below any wrong formula's
                    ;; error (a wrong constant or sign moves values by 1e-3 or more).
                    (assert.is_true (<= err 1e-8)
                                    (string.format "%s node %d at %.17g %.17g %.17g: translated %.17g, scalar %.17g"
                                                   file k x y z got want))))
                (print (string.format "examples: %s node %d: factor %.3g, largest difference %.3g of 1 + |d| over %d points"
                                      file k node.lipschitz worst points-per-node))))))))

    (it "examples/mandelbulb.fnl draws whole: no ray of the CPU reference runs out of its 500 steps"
      (fn []
        (let [{: w : h : on-bulb : out-of-steps : max-steps : most} (march-all "examples/mandelbulb.fnl")]
          (print (string.format "examples: mandelbulb at %dx%d: %d rays on the bulb, %d out of %d steps, at most %d steps"
                                w h on-bulb (length out-of-steps) max-steps most))
          ;; The default budget: the scene sets none.
          (assert.are.equal 500 max-steps)
          ;; The bulb fills a good part of the picture (else no ray tested it).
          (assert.is_true (> on-bulb (* 0.2 w h)) (.. on-bulb " rays hit the bulb"))
          (assert.are.equal 0 (length out-of-steps)
                            (let [r (. out-of-steps 1)]
                              (when r (string.format "pixel %d %d ran out of steps" r.x r.y)))))))

    ;; Without :lipschitz 1 :trust-lipschitz true the loader measures 498 outside the
    ;; bulb (the estimate of the 8th turn changes by hundreds per unit at the scale of
    ;; its detail, 8^-8, far below the marcher's), divides each step by 1.1 times
    ;; that, 548, and 377 of the 3072 rays (those that come near the bulb) run out of
    ;; their 500 steps: the picture shows the floor or the sky where the bulb should be. Turn this into `it`
    ;; when the measure of src/sdf/custom.fnl gives a factor near 1 for it.
    (pending "examples/mandelbulb.fnl draws whole with its factor measured, not declared (measured 498, steps divided by 548: 377 of 3072 rays out of steps; waits for src/sdf/custom.fnl)"
      (fn []
        (let [text (with-open [f (assert (io.open "examples/mandelbulb.fnl"))] (f:read :*a))
              (measured n) (text:gsub ":lipschitz 1 :trust%-lipschitz true" "")
              file "test/out/mandelbulb-measured.fnl"
              _ (os.execute "mkdir -p test/out")
              _ (with-open [f (assert (io.open file :w))] (f:write measured))
              {: out-of-steps : on-bulb : w : h} (march-all file)]
          (assert.are.equal 1 n)
          (assert.are.equal 0 (length out-of-steps))
          (assert.is_true (> on-bulb (* 0.2 w h)) (.. on-bulb " rays hit the bulb")))))))

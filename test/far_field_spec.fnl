;; The far field (issue 25): far from an object its value approaches the distance to
;; it, whatever Lipschitz corrections it holds, so rays, shadow rays and occlusion take
;; long steps there. Checked on every showcase scene's tree objects against the true
;; distance, estimated from points found on each object's surface.

(local load (require :src.scene.load))
(local plan-mod (require :src.render.plan))
(local emit-lua (require :src.sdf.emit-lua))
(local lower (require :src.sdf.lower))

(local showcase ["seed" "gallery" "organic" "colonnade" "twisted-tower" "flower"
                 "machined-part" "platonic-shelf" "lighting" "spheres" "flat"])

(fn scene-plan [name ?options]
  (let [s (assert (load.load-file (.. "scenes/" name ".fnl")))]
    (values (assert (plan-mod.scene->plan s ?options)) s)))

;; A small deterministic generator: the same points every run.
(fn generator [seed]
  (var state seed)
  (fn []
    (set state (% (+ (* state 1103515245) 12345) 2147483648))
    (/ state 2147483648)))

(fn unit [rnd]
  ;; A direction uniform on the sphere.
  (let [z (- (* 2 (rnd)) 1)
        a (* 2 math.pi (rnd))
        r (math.sqrt (- 1 (* z z)))]
    [(* r (math.cos a)) (* r (math.sin a)) z]))

(fn surface-points [f centre half rnd n]
  "Points on the surface of the object of distance bound `f`: rays from a sphere
around its box toward random points in the box, each marched until `f` is under
1e-4 (a bound never steps through the surface). Returns a flat list x y z ..."
  (let [[cx cy cz] centre
        [hx hy hz] half
        reach (+ 1 (math.sqrt (+ (* hx hx) (* hy hy) (* hz hz))))
        out []]
    (for [_ 1 n]
      (let [[ux uy uz] (unit rnd)
            ox (+ cx (* reach ux)) oy (+ cy (* reach uy)) oz (+ cz (* reach uz))
            tx (+ cx (* hx (- (* 2 (rnd)) 1)))
            ty (+ cy (* hy (- (* 2 (rnd)) 1)))
            tz (+ cz (* hz (- (* 2 (rnd)) 1)))
            dx (- tx ox) dy (- ty oy) dz (- tz oz)
            len (math.sqrt (+ (* dx dx) (* dy dy) (* dz dz)))
            (dx dy dz) (values (/ dx len) (/ dy len) (/ dz len))]
        (var t 0)
        (var done? false)
        (for [_ 1 2000 &until done?]
          (let [x (+ ox (* t dx)) y (+ oy (* t dy)) z (+ oz (* t dz))
                d (f x y z)]
            (if (< d 1e-4)
                (do (set done? true)
                    (table.insert out x) (table.insert out y) (table.insert out z))
                (> t (* 3 reach)) (set done? true)
                (set t (+ t d)))))))
    out))

(fn nearest [points x y z]
  (var best math.huge)
  (for [i 1 (length points) 3]
    (let [dx (- x (. points i)) dy (- y (. points (+ i 1))) dz (- z (. points (+ i 2)))]
      (set best (math.min best (+ (* dx dx) (* dy dy) (* dz dz))))))
  (math.sqrt best))

(fn far-ratios [name ?options]
  "For each finite tree object of scene `name`: the smallest ratio of its value to its
true distance (estimated from its surface points, so the estimate is at least the
true distance) at points 10 to 50 units from it. A list of {:path :ratio :value :true}."
  (let [(p s) (scene-plan name ?options)
        ev (emit-lua.compile p.tape)
        rnd (generator 12345)
        out []]
    (each [i o (ipairs p.tape.objects)]
      (let [info (. o.info :children 1)
            tree (. s.objects o.index :tree)
            centre (or (?. tree :pos) [0 0 0])]
        ;; (The scene's flat objects, its plane, are on the tape too: trees only.)
        (when (and tree info info.bounds)
          (let [f (. ev.distance i)
                [hx hy hz] info.bounds
                radius (math.sqrt (+ (* hx hx) (* hy hy) (* hz hz)))
                points (surface-points f centre info.bounds rnd 600)
                [cx cy cz] centre]
            (var worst {:path o.info.path :ratio math.huge})
            (when (> (length points) 0)
              (for [_ 1 24]
                (let [[ux uy uz] (unit rnd)
                      gap (+ 10 (* 40 (rnd)))
                      ;; At least `gap` from everything inside the box's sphere.
                      r (+ radius gap)
                      x (+ cx (* r ux)) y (+ cy (* r uy)) z (+ cz (* r uz))
                      truth (nearest points x y z)
                      value (f x y z)]
                  (when (< (/ value truth) worst.ratio)
                    (set worst {:path o.info.path :ratio (/ value truth) : value :true truth}))))
              (table.insert out worst))))))
    out))

(describe "the far field"
  (fn []
    (it "gives at least half the true distance 10 to 50 units from every showcase object"
      (fn []
        (var checked 0)
        (each [_ name (ipairs showcase)]
          (let [(p) (scene-plan name)]
            (when p.tape
              (each [_ r (ipairs (far-ratios name))]
                (set checked (+ checked 1))
                (assert (>= r.ratio 0.5)
                        (string.format "%s %s: %.3g at a point %.3g from it (ratio %.2f)"
                                       name r.path r.value r.true r.ratio))
                ;; A bound: never more than the distance (the estimate is at least
                ;; the true distance, within the surface points' spacing).
                (assert (<= r.ratio 1.0001)
                        (string.format "%s %s: %.6g overshoots %.6g" name r.path r.value r.true))))))
        ;; Every showcase scene with trees took part.
        (assert (> checked 20) (.. "only " checked " objects checked"))))

    (it "was missing before: twist, bend and displacement kept values near 1 / k"
      (fn []
        ;; The same check without far fields fails on twisted-tower, which is what
        ;; makes the test above able to fail.
        (let [worst (accumulate [w math.huge _ r (ipairs (far-ratios "twisted-tower"
                                                                     {:far-field? false}))]
                      (math.min w r.ratio))]
          (assert (< worst 0.2) (.. "without far fields the worst ratio is " worst)))))

    (it "takes the issue's probe point 28 units from the tower to more than 14"
      (fn []
        ;; printf '30 10 5\n' | love . --probe scenes/twisted-tower.fnl printed 1.83:
        ;; the tree objects alone (the ground plane is 5 away).
        (let [(p s) (scene-plan "twisted-tower")
              ev (emit-lua.compile p.tape)
              d (accumulate [m math.huge i o (ipairs p.tape.objects)]
                  (if (. s.objects o.index :tree) (math.min m ((. ev.distance i) 30 10 5)) m))]
          (assert (> d 14) (.. "tree objects' distance at (30 10 5): " d)))))

    (it "guards each object by its box and marks far fields in --tree"
      (fn []
        (let [(p s) (scene-plan "twisted-tower")
              lines (table.concat (lower.describe p.tape) "\n")]
          ;; Every tree object (not the flat ground plane, a primitive).
          (each [_ o (ipairs p.tape.objects)]
            (when (. s.objects o.index :tree) (assert.truthy o.guard)))
          ;; The tower stands on z = 0: its box reaches 0.9 below (the stairs' blend
          ;; radius), not as deep as it is tall as its symmetric bounds do (±9.5).
          (let [tower (. p.tape.objects 2 :info :children 1)]
            (assert.are.equal -9.5 (- (. tower.bounds 3)))
            (assert.is_true (< (math.abs (- (. tower.box :lo 3) -0.9)) 1e-9))
            (assert.is_true (< (math.abs (- (. tower.box :hi 3) 9.5)) 1e-9)))
          (assert.truthy (lines:find "far field" 1 true))
          ;; Off for the benchmark's before: the previous tape, no guards.
          (let [(q) (scene-plan "twisted-tower" {:far-field? false})]
            (each [_ o (ipairs q.tape.objects)] (assert.is_nil o.guard))
            (assert.falsy (: (table.concat (lower.describe q.tape) "\n") :find "far field" 1 true))))))))

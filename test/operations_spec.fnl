;; tier: fast
;; Every operation, through the whole path a scene takes (loader, lowering to the tape,
;; the Lua emitter), against an oracle written out here from the maths and the
;; hand-written distances of test/oracles.fnl; then the properties its class promises:
;; exact nodes have |gradient| = 1 outside and project onto their surface, bounds never
;; exceed the distance to a dense sample of their surface, and every node, after the
;; Lipschitz correction, changes by at most its step per unit.

(local load (require :src.scene.load))
(local plan-mod (require :src.render.plan))
(local emit-lua (require :src.sdf.emit-lua))
(local operations (require :src.sdf.operations))
(local oracles (require :test.support.oracles))
(local {: lcg : gradient : surface-samples : nearest : outside-points}
  (require :test.support.fields))

(local {: sqrt : abs : min : max : sin : cos : exp : log : pi : floor} math)

(fn evaluator [node-text ?far-field?]
  "The CPU distance and material functions of the one tree object in `node-text`,
and its node info. The operation's own formula, without the far field (the max with
its bounding box's distance, test/far_field_spec.fnl), unless `?far-field?`."
  (let [(scene err) (load.load-string (.. "{:objects [" node-text "]}") "op.fnl")
        _ (assert scene err)
        (plan perr) (plan-mod.scene->plan scene {:far-field? (= true ?far-field?)})
        _ (assert plan perr)
        _ (assert plan.tape "not a tree")
        ev (emit-lua.compile plan.tape)]
    ;; The object's info is its outermost node's: under the implicit translation.
    (let [info (. plan.tape.objects 1 :info)]
      (values (. ev.distance 1) (. ev.material 1)
              (if info.implicit? (. info.children 1) info)))))

(local sphere oracles.sphere)
(local box oracles.box)

(fn clamp [v lo hi] (max lo (min hi v)))

;; Each operation's example nodes (its descriptor's :examples) by kind.
(local examples
  (collect [_ d (ipairs operations.all)]
    (values d.kind (icollect [_ e (ipairs (or d.examples []))] e))))

(fn example [name]
  ;; The node of the example called `name`.
  (accumulate [found nil _ es (pairs examples)]
    (or found (accumulate [f nil _ e (ipairs es)] (or f (when (= e.name name) e.node))))))

;; name, node, oracle (fn [x y z]) -> d (and for a node no operation's example has,
;; the sampling half extents of its promises)
(local cases
  [[:translate (example :translate)
    #(sphere $1 $2 $3 [1 2 3] 1)]
   [:rotate-angles (example :rotate-angles)
    #(box $1 $2 $3 [0 0 0] [0.5 1 0.5])]
   [:rotate-axis (example :rotate-axis)
    #(box $1 $2 $3 [0 0 0] [0.5 1 0.5])]
   [:scale (example :scale)
    #(box $1 $2 $3 [0 0 0] [1 2 1])]
   [:shorthand "{:kind :box :size [2 1 1] :pos [1 0 0] :rotate [0 0 90] :scale 2}"
    #(box $1 $2 $3 [1 0 0] [1 2 1]) [3 3 2]]
   [:stretch (example :stretch)
    #(* (sphere (/ $1 2) $2 $3 [0 0 0] 1) 1)]
   [:mirror (example :mirror)
    #(min (sphere $1 $2 $3 [2 0 0] 1) (sphere $1 $2 $3 [-2 0 0] 1))]
   [:elongate (example :elongate)
    #(- (sqrt (+ (^ (- $1 (clamp $1 -1 1)) 2) (* $2 $2) (* $3 $3))) 1)]
   [:twist (example :twist)
    (let [k (/ pi 6) rho0 (sqrt 0.5)]
      (fn [x y z]
        (let [c (cos (* k z)) s (sin (* k z))
              v (* k (max rho0 (sqrt (+ (* x x) (* y y)))))]
          (/ (box (+ (* c x) (* s y)) (- (* c y) (* s x)) z [0 0 0] [0.5 0.5 1.5])
             (* 0.5 (+ v (sqrt (+ (* v v) 4))))))))]
   [:bend (example :bend)
    (let [k (/ pi 9) rho0 (sqrt (+ 2.25 0.0625))]
      (fn [x y z]
        (let [c (cos (* k x)) s (sin (* k x))]
          (/ (box (- (* c x) (* s z)) y (+ (* s x) (* c z)) [0 0 0] [1.5 0.5 0.25])
             (+ 1 (* k (max rho0 (sqrt (+ (* x x) (* z z))))))))))]
   [:repeat (example :repeat)
    (fn [x y z]
      (var d math.huge)
      (for [k -60 60] (set d (min d (sphere x y z [(+ 0.8 (* 3 k)) 0 0] 0.5))))
      d)]
   [:repeat-limited (example :repeat-limited)
    (fn [x y z]
      (var d math.huge)
      (for [i -2 2] (for [j -1 1] (set d (min d (box x y z [(* 3 i) (* 3 j) 0] [0.5 0.5 0.5])))))
      d)]
   [:polar (example :polar)
    (fn [x y z]
      (var d math.huge)
      (for [i 0 5]
        (let [a (* i (/ pi 3)) c (cos a) s (sin a)]
          (set d (min d (sphere x y z [(- (* c 2) (* s 0.3)) (+ (* s 2) (* c 0.3)) 0] 0.5)))))
      d)]
   [:round (example :round)
    #(- (box $1 $2 $3 [0 0 0] [0.5 0.5 0.5]) 0.2)]
   [:onion (example :onion)
    #(- (abs (- (abs (sphere $1 $2 $3 [0 0 0] 1)) 0.2)) 0.1)]
   [:displace (example :displace)
    (let [L (+ 1 (* 0.1 5 (sqrt 3)))]
      #(/ (+ (sphere $1 $2 $3 [0 0 0] 1) (* 0.1 (sin (* 5 $1)) (sin (* 5 $2)) (sin (* 5 $3)))) L))]
   [:union (example :union)
    #(min (sphere $1 $2 $3 [-2 0 0] 1) (box $1 $2 $3 [2 0 0] [0.5 0.5 0.5]) (sphere $1 $2 $3 [0 2 0] 0.5))]
   [:intersection (example :intersection)
    #(max (sphere $1 $2 $3 [0 0 0] 1) (box $1 $2 $3 [0 0 0] [0.75 0.75 0.75]))]
   [:subtraction (example :subtraction)
    #(max (box $1 $2 $3 [0 0 0] [1 1 1]) (- (sphere $1 $2 $3 [0 0 0] 1.2)) (- (sphere $1 $2 $3 [1 1 1] 0.5)))]
   [:xor (example :xor)
    #(let [a (sphere $1 $2 $3 [0 0 0] 1) b (sphere $1 $2 $3 [1 0 0] 1)] (max (min a b) (- (max a b))))]
   [:smooth-union (example :smooth-union)
    #(let [a (sphere $1 $2 $3 [-0.8 0 0] 1) b (sphere $1 $2 $3 [0.8 0 0] 1)
           h (clamp (+ 0.5 (/ (- b a) 1)) 0 1)]
       ;; Written as the classic form: min(a, b) - r/4 * s^2 with s = max(r - |a - b|, 0) / r.
       (let [s (/ (max (- 0.5 (abs (- a b))) 0) 0.5)]
         (- (min a b) (* 0.125 s s))))]
   [:smooth-union-exp (example :smooth-union-exp)
    #(let [a (sphere $1 $2 $3 [-0.8 0 0] 1) b (sphere $1 $2 $3 [0.8 0 0] 1)]
       (* -0.2 (log (+ (exp (/ a -0.2)) (exp (/ b -0.2))))))]
   [:smooth-intersection (example :smooth-intersection)
    #(let [a (sphere $1 $2 $3 [0 0 0] 1) b (box $1 $2 $3 [0 0 0] [0.75 0.75 0.75])
           s (/ (max (- 0.3 (abs (- a b))) 0) 0.3)]
       (+ (max a b) (* 0.075 s s)))]
   [:smooth-subtraction (example :smooth-subtraction)
    #(let [a (box $1 $2 $3 [0 0 0] [1 1 1]) b (- (sphere $1 $2 $3 [0 0 0] 1.2))
           s (/ (max (- 0.3 (abs (- a b))) 0) 0.3)]
       (+ (max a b) (* 0.075 s s)))]
   [:chamfer-union (example :chamfer-union)
    #(let [a (box $1 $2 $3 [0 0 0] [1.5 1.5 0.5]) b (box $1 $2 $3 [0 0 1] [0.5 0.5 1.5])]
       (min a b (* 0.5 (- (+ a b) 0.4))))]
   [:stairs-union (example :stairs-union)
    ;; The staircase's corner points: the union with every step's quarter plane.
    #(let [a (box $1 $2 $3 [0 0 0] [1.5 1.5 0.5]) b (box $1 $2 $3 [0 0 1] [0.5 0.5 1.5])]
       (min a b (max (- a 0.2) (- b 0.6)) (max (- a 0.4) (- b 0.4)) (max (- a 0.6) (- b 0.2))))]])

(describe "operations against their oracles"
  (fn []
    (each [_ [name text oracle] (ipairs cases)]
      (it (.. name ": the CPU evaluator from the tape equals the oracle")
        (fn []
          (let [(f) (evaluator text)
                rand (lcg 3)]
            (for [_ 1 500]
              (let [x (* 4 (- (* 2 (rand)) 1)) y (* 4 (- (* 2 (rand)) 1)) z (* 4 (- (* 2 (rand)) 1))
                    got (f x y z)
                    want (oracle x y z)]
                ;; Both are double precision; the order of operations differs (a
                ;; rotation by a matrix of cos 90 = 6e-17): 1e-9 is far above that.
                (assert.is_true (< (abs (- got want)) 1e-9)
                                (string.format "%s at (%g %g %g): tape %.12g, oracle %.12g"
                                               name x y z got want))))))))))

(fn promise-cases []
  ;; [name node extent]: the cases with their own extent, then every operation's
  ;; examples.
  (let [out (icollect [_ [name text _ extent] (ipairs cases)]
              (when extent [name text extent]))]
    (each [_ d (ipairs operations.all)]
      (each [_ e (ipairs (. examples d.kind))]
        (table.insert out [e.name e.node e.extent])))
    out))

(describe "operations keep their promises"
  (fn []
    (it "every operation has an example"
      (fn []
        (each [_ d (ipairs operations.all)]
          (assert.is_true (> (length (. examples d.kind)) 0)
                          (.. d.kind ": no :examples in its descriptor")))))
    ;; Every operation's examples, and the cases of none (the shorthand), with the far
    ;; field, as the marcher sees them.
    (each [_ [name text box-extent] (ipairs (promise-cases))]
      (let [(f _ info) (evaluator text true)]
        (it (.. name " (" info.class ", Lipschitz " info.lipschitz "): changes at most 1 per unit after correction")
          (fn []
            (let [rand (lcg 5)]
              (for [_ 1 300]
                (let [[hx hy hz] box-extent
                      x (* hx (- (* 2 (rand)) 1)) y (* hy (- (* 2 (rand)) 1)) z (* hz (- (* 2 (rand)) 1))
                      (gx gy gz) (gradient f x y z 1e-6)
                      g (sqrt (+ (* gx gx) (* gy gy) (* gz gz)))]
                  ;; Differences over 2e-6 carry rounding of about 1e-10 / 1e-6.
                  (assert.is_true (<= g 1.0001)
                                  (string.format "%s at (%g %g %g): |gradient| %.6f" name x y z g)))))))
        (when (= info.class :exact)
          (it (.. name " (exact): |gradient| = 1 and projects onto the surface, outside")
            (fn []
              (let [pts (outside-points f box-extent 200 9)]
                (var checked 0)
                (each [_ [x y z] (ipairs pts)]
                  (let [(gx gy gz) (gradient f x y z 1e-5)
                        (ax ay az) (gradient f x y z 4e-5)]
                    (when (< (+ (abs (- gx ax)) (abs (- gy ay)) (abs (- gz az))) 1e-4)
                      (set checked (+ checked 1))
                      (let [g (sqrt (+ (* gx gx) (* gy gy) (* gz gz)))
                            v (f x y z)
                            on (f (- x (* v gx)) (- y (* v gy)) (- z (* v gz)))]
                        (assert.is_true (< (abs (- g 1)) 1e-4)
                                        (string.format "%s at (%g %g %g): |gradient| %.6f" name x y z g))
                        (assert.is_true (< (abs on) (* 1e-4 (+ 1 v)))
                                        (string.format "%s at (%g %g %g): lands at %g" name x y z on))))))
                (assert.is_true (> checked (* 0.7 (length pts)))
                                (.. name ": only " checked " of " (length pts) " points checked"))))))
        (it (.. name ": never above the distance to the densely sampled surface")
          (fn []
            (let [(surface spacing) (surface-samples f box-extent 40)
                  pts (outside-points f box-extent 60 13)]
              (assert.is_true (> (length surface) 100) (.. name ": no surface found"))
              (each [_ [x y z] (ipairs pts)]
                (let [v (f x y z) est (nearest surface x y z)]
                  (assert.is_true (<= v (+ est 1e-6))
                                  (string.format "%s at (%g %g %g): %g above the sampled distance %g"
                                                 name x y z v est)))))))))))

(describe "materials"
  (fn []
    (it "a smooth union blends its children's colours by the distance weight"
      (fn []
        (let [(_ m) (evaluator "{:kind :smooth-union :radius 1 :children [{:kind :sphere :radius 1 :pos [-1 0 0] :color [1 0 0]} {:kind :sphere :radius 1 :pos [1 0 0] :color [0 0 1]}]}")
              (_ r g b mirror) (m 0 0 0.5)
              (_ r2 _ b2) (m -1.5 0 0.5)]
          ;; Equidistant: half and half.
          (assert.is_true (< (abs (- r 0.5)) 1e-12))
          (assert.is_true (< (abs (- b 0.5)) 1e-12))
          (assert.are.equal 0 g)
          (assert.are.equal 1 mirror)
          ;; Nearer the red sphere: mostly red.
          (assert.is_true (and (> r2 0.9) (< b2 0.1))))))
    (it "a subtraction shows the cutter's material on the cut"
      (fn []
        (let [(_ m) (evaluator "{:kind :subtraction :color [0 1 0] :children [{:kind :box :size [2 2 2]} {:kind :sphere :radius 1 :pos [1 0 0] :color [1 0 0] :mirror 0.25}]}")
              (d r g b mirror) (m 0.05 0 0)
              (_ r2 g2) (m -1.05 0 0)]
          (assert.is_true (< d 0.1))
          (assert.are.same [1 0 0 0.25] [r g b mirror])
          (assert.are.same [0 1] [r2 g2]))))
    (it "children inherit the nearest material above them; the default is the article's"
      (fn []
        (let [(_ m) (evaluator "{:kind :union :color [0.2 0.3 0.4] :mirror 0.5 :children [{:kind :sphere} {:kind :box :pos [3 0 0] :color [1 1 0]}]}")
              (_ mr mg mb mm) (m 0 0 1.1)
              (_ br bg bb bm) (m 3 0 0.6)
              (_ dm) (evaluator "{:kind :union :children [{:kind :sphere}]}")
              (_ dr dg db dmirror) (dm 0 0 1.1)]
          (assert.are.same [0.2 0.3 0.4 0.5] [mr mg mb mm])
          (assert.are.same [1 1 0 0.5] [br bg bb bm])
          (assert.are.same [1 1 1 1] [dr dg db dmirror]))))))

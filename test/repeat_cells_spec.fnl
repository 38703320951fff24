;; tier: fast
;; How few cells a repetition evaluates its child in (src/sdf/lower.fnl, Repetitions):
;; one cell for a centred child even along the repeated axes, the same distances as
;; every cell; a costly child clear of its cell's walls in its own cell only, its
;; neighbours by their boxes: a bound everywhere, the distance near the copies. Each
;; against brute force over the copies, on the CPU evaluator (the GPU's code is the
;; same tape; test/gpu_vs_cpu_spec.fnl holds them together).

(local load (require :src.scene.load))
(local plan-mod (require :src.render.plan))
(local emit-lua (require :src.sdf.emit-lua))
(local {: sphere : box} (require :test.support.oracles))
(local {: lcg} (require :test.support.fields))

(local {: abs : max : min} math)

(fn plan-of [node-text]
  (let [(scene err) (load.load-string (.. "{:objects [" node-text "]}") "cells.fnl")]
    (assert scene err)
    (assert (plan-mod.scene->plan scene {:far-field? false}))))

(fn cells-of [plan]
  ;; The first :cells instruction of the first object.
  (accumulate [found nil _ ins (ipairs (. plan.tape.objects 1 :code)) &until found]
    (when (= ins.op :cells) ins)))

(fn distance-of [plan]
  (. (emit-lua.compile plan.tape) :distance 1))

(fn points [n half seed]
  ;; n points in the box of half extents `half` about the origin.
  (let [rand (lcg seed)]
    (fcollect [_ 1 n]
      (icollect [_ h (ipairs half)] (* h (- (* 2 (rand)) 1))))))

(describe "repetition cells"
  (fn []
    (it "evaluates a centred even child in its own cell only, with every cell's distances"
      (fn []
        ;; Floor tiles: a box centred in each cell of a 2 x 2 grid.
        (let [p (plan-of "{:kind :repeat :period [2 2 0] :children [{:kind :box :size [1.6 1.2 0.2]}]}")
              f (distance-of p)]
          (assert.are.equal 1 (. (cells-of p) :count))
          (each [_ [x y z] (ipairs (points 400 [9 9 1.5] 7))]
            (var brute math.huge)
            (for [i -6 6]
              (for [j -6 6]
                (set brute (min brute (box x y z [(* 2 i) (* 2 j) 0] [0.8 0.6 0.1])))))
            (assert.is_true (< (abs (- (f x y z) brute)) 1e-9))))
        ;; Limited: past the last copy the clamped cell is still the nearest.
        (let [p (plan-of "{:kind :repeat :period [3 0 0] :count [1 0 0] :children [{:kind :sphere :radius 1}]}")
              f (distance-of p)]
          (assert.are.equal 1 (. (cells-of p) :count))
          (each [_ [x y z] (ipairs (points 200 [9 2 2] 8))]
            (let [brute (min (sphere x y z [-3 0 0] 1) (sphere x y z [0 0 0] 1) (sphere x y z [3 0 0] 1))]
              (assert.is_true (< (abs (- (f x y z) brute)) 1e-9)))))))

    (it "keeps the neighbours of a child off centre or not even along a repeated axis"
      (fn []
        ;; Off centre along x (repeated); off centre along z only (not repeated) is fine.
        (assert.are.equal 2 (. (cells-of (plan-of "{:kind :repeat :period [3 0 0] :children [{:kind :sphere :radius 0.5 :pos [0.8 0 0]}]}")) :count))
        (assert.are.equal 1 (. (cells-of (plan-of "{:kind :repeat :period [3 0 0] :children [{:kind :sphere :radius 0.5 :pos [0 0 0.8]}]}")) :count))
        ;; A torus is not even in x (a ring): two cells, and no box for its neighbour
        ;; (a primitive costs about what its box does).
        (let [c (cells-of (plan-of "{:kind :repeat :period [3 0 0] :children [{:kind :torus}]}"))]
          (assert.are.equal 2 c.count)
          (assert.is_nil c.near?))
        ;; A polar repetition keeps both sectors.
        (assert.are.equal 2 (. (cells-of (plan-of "{:kind :polar :count 6 :children [{:kind :sphere :radius 0.2 :pos [1 0 0]}]}")) :count))))

    (it "draws a costly child's neighbours by their boxes: a bound, exact near the copies"
      (fn []
        ;; A column cut by a sphere (a subtraction: not even), 1 x 1 in a period of 4.
        (let [node "{:kind :repeat :period [4 0 0] :children [{:kind :subtraction :children [{:kind :box :size [1 1 2]} {:kind :sphere :radius 0.4 :pos [0.5 0 0]}]}]}"
              p (plan-of node)
              f (distance-of p)
              one (fn [x y z cx] (max (box x y z [cx 0 0] [0.5 0.5 1]) (- (sphere x y z [(+ cx 0.5) 0 0] 0.4))))]
          (assert.is_table (. (cells-of p) :near?))
          (assert.are.equal :bound (. p.tape.objects 1 :info :children 1 :class))
          (each [_ [x y z] (ipairs (points 600 [14 3 3] 9))]
            (var brute math.huge)
            (for [i -5 5] (set brute (min brute (one x y z (* 4 i)))))
            (let [d (f x y z)]
              ;; Never above the distance (a 1e-9 for rounding); the same where the
              ;; nearest copy is nearer than the neighbours' boxes can be (1.5 away).
              (assert.is_true (<= d (+ brute 1e-9)))
              (when (< brute 1.4)
                (assert.is_true (< (abs (- d brute)) 1e-9))))))
        ;; Limited: past the end, the clamped neighbour is the own copy, not its box.
        (let [p (plan-of "{:kind :repeat :period [4 0 0] :count [1 0 0] :children [{:kind :subtraction :children [{:kind :box :size [1 1 2]} {:kind :sphere :radius 0.4 :pos [0.5 0 0]}]}]}")
              f (distance-of p)
              d (f 9 0 0)]
          (assert.is_true (< (abs (- d (box 9 0 0 [4 0 0] [0.5 0.5 1]))) 1e-9)))
        ;; A child that reaches within a tenth of a period of its cell's wall keeps
        ;; its neighbours whole.
        (assert.is_nil (. (cells-of (plan-of "{:kind :repeat :period [4 0 0] :children [{:kind :subtraction :children [{:kind :box :size [3.4 1 2]} {:kind :sphere :radius 0.4}]}]}")) :near?))))

    (it "writes a repetition's GLSL for the axes it repeats along, without a loop"
      (fn []
        (let [codegen (require :src.render.codegen)
              p (plan-of "{:kind :repeat :period [2 0 3] :children [{:kind :torus}]}")
              text (assert (codegen.shader p :core))
              body (text:match "vec3 opRepeatXZ%(.-\n}")]
          (assert.is_string body)
          (assert.falsy (body:find "for (" 1 true))
          (assert.falsy (body:find "p.y" 1 true))
          (assert.falsy (text:find "vec3 opRepeat(" 1 true))
          ;; Which axes is structure: another set is another key, the same set with
          ;; other periods the same key.
          (assert.are_not.equal p.tape.key (. (plan-of "{:kind :repeat :period [2 3 0] :children [{:kind :torus}]}") :tape :key))
          (assert.are.equal p.tape.key (. (plan-of "{:kind :repeat :period [5 0 1] :children [{:kind :torus}]}") :tape :key)))))

    (it "turns a polar repetition's point by series within 60 degrees, from 3 sectors on"
      (fn []
        (let [codegen (require :src.render.codegen)
              operations (require :src.sdf.operations)
              polar (operations.lookup :polar)
              narrow (operations.variant polar {:count 12})
              ;; Off the x axis: not symmetric in y, so not folded (see below).
              shader #(assert (codegen.shader (plan-of (.. "{:kind :polar :count " $ " :children [{:kind :sphere :radius 0.2 :pos [1 0.1 0]}]}")) :core))]
          (assert.truthy (: (shader 3) :find "opPolarNarrow(" 1 true))
          (assert.falsy (: (shader 2) :find "opPolarNarrow(" 1 true))
          ;; The series as the GLSL writes them (Horner in b^2), against math.sin and
          ;; math.cos over the widest angle they meet (half of a third of a turn):
          ;; within float32's rounding there.
          (fn series [name]
            (let [line (narrow.glsl:match (.. "float " name " = ([^;]+);"))
                  coefficients (icollect [v (line:gmatch "[-]?%d+%.%d+e?[-+]?%d*")] (tonumber v))]
              ;; Up to b^11 for sin, b^12 for cos.
              (assert.are.equal (if (= name "s") 6 7) (length coefficients))
              (fn [b]
                (var acc 0)
                (for [i (length coefficients) 1 -1]
                  (set acc (+ (. coefficients i) (* b b acc))))
                (if (= name "s") (* b acc) acc))))
          (let [sin-series (series "s") cos-series (series "c")]
            (for [i -100 100]
              (let [b (* (/ i 100) (/ math.pi 3))]
                (assert.is_true (< (abs (- (sin-series b) (math.sin b))) 1e-8))
                (assert.is_true (< (abs (- (cos-series b) (math.cos b))) 1e-8))))))))

    (it "folds a polar repetition of a child symmetric in y into its half sector"
      (fn []
        (let [codegen (require :src.render.codegen)
              operations (require :src.sdf.operations)
              polar (operations.lookup :polar)
              shader #(assert (codegen.shader (plan-of (.. "{:kind :polar :count 12 :children [" $ "]}")) :core))
              folded? #(not= nil (: (shader $) :find "opPolarFold4x2(" 1 true))]
          ;; Symmetric in y: centred on the x axis, mirrored across y, turned about y,
          ;; cut by another such child.
          (assert.is_true (folded? "{:kind :sphere :radius 0.2 :pos [1 0 0]}"))
          (assert.is_true (folded? "{:kind :mirror :normal [0 1 0] :children [{:kind :sphere :radius 0.2 :pos [1 0.3 0]}]}"))
          (assert.is_true (folded? "{:kind :ellipsoid :radii [0.5 0.2 0.1] :rotate [0 20 0] :pos [1 0 0]}"))
          (assert.is_true (folded? "{:kind :subtraction :children [{:kind :capped-cylinder :radius 0.3} {:kind :capped-cylinder :radius 0.05 :pos [0.3 0 0]}]}"))
          (assert.falsy (: (shader "{:kind :sphere :radius 0.2 :pos [1 0 0]}") :find "atan(" 1 true))
          ;; What the lowering calls symmetric in y is: the same distance and
          ;; material at (x, -y, z) as at (x, y, z), on the CPU evaluator.
          (each [_ child (ipairs ["{:kind :mirror :normal [0 1 0] :children [{:kind :sphere :radius 0.2 :pos [1 0.3 0]}]}"
                                  "{:kind :ellipsoid :radii [0.5 0.2 0.1] :rotate [0 20 0] :pos [1 0 0.2]}"
                                  "{:kind :smooth-subtraction :radius 0.1 :children [{:kind :torus :pos [0 0 0.1]} {:kind :capped-cylinder :radius 0.05 :pos [0.3 0 0]}]}"
                                  "{:kind :polar :count 5 :children [{:kind :box :size [0.3 0.1 0.1] :pos [1 0 0]}]}"])]
            (let [p (plan-of child)
                  info (. p.tape.objects 1 :info)
                  ev (emit-lua.compile p.tape)
                  d (. ev.distance 1)
                  m (. ev.material 1)]
              (assert.is_true (. info.symmetric 2) child)
              (each [_ [x y z] (ipairs (points 100 [2 2 1] 11))]
                (assert.is_true (< (abs (- (d x y z) (d x (- y) z))) 1e-12) child)
                (assert.are.same [(m x y z)] [(m x (- y) z)]))))
          ;; Not: off the axis, turned about x, displaced (its sines are odd in y).
          (assert.is_false (folded? "{:kind :sphere :radius 0.2 :pos [1 0.1 0]}"))
          (assert.is_false (folded? "{:kind :ellipsoid :radii [0.5 0.2 0.1] :rotate [20 0 0] :pos [1 0 0]}"))
          (assert.is_false (folded? "{:kind :displace :children [{:kind :sphere :radius 0.2 :pos [1 0 0]}]}"))
          ;; The GLSL's folds, run here as its lines say with the values its form
          ;; packs, give the point of the copy the CPU form (atan) finds, or that
          ;; point mirrored in y, for both cells: for every count, on points around.
          (each [_ n (ipairs [2 3 4 5 6 7 8 9 10 11 12 13 16 24 31 100 255 256])]
            (let [form (operations.variant polar {:count n} {:symmetric [true true true]})
                  text form.glsl
                  v (form.pack {:count n})
                  [sector tc ts] v
                  folds (icollect [row part (text:gmatch "min%(dot%(q, fold(%d)%.(%a%a)%), 0%.0%)")]
                          (let [at (+ 4 (* 4 (- (tonumber row) 1)) (if (= part "zw") 2 0))]
                            [(. v at) (. v (+ at 1))]))
                  both? (not= nil (text:find "abs(p.xy)" 1 true))
                  swap? (not= nil (text:find "max(q.x, q.y), min(q.x, q.y)" 1 true))]
              (assert.is_true (or both? (not= nil (text:find "vec2(p.x, abs(p.y))" 1 true))))
              (assert.are.equal (= 0 (% n 2)) both?)
              (assert.are.equal (= 0 (% n 4)) swap?)
              (assert.is_true (<= (length folds) 8))
              (each [_ [x y] (ipairs (points 300 [3 3 0] n))]
                (var (qx qy) (values (if both? (abs x) x) (abs y)))
                (when swap? (set (qx qy) (values (max qx qy) (min qx qy))))
                (each [_ [nx ny] (ipairs folds)]
                  (let [d (* 2 (min 0 (+ (* qx nx) (* qy ny))))]
                    (set (qx qy) (values (- qx (* d nx)) (- qy (* d ny))))))
                (let [(ax ay) (form.cpu 0 x y 0 sector)
                      (bx by) (form.cpu 1 x y 0 sector)
                      sign (if (< (abs (- qy ay)) 1e-9) 1 -1)
                      ;; The neighbour's point: the folded one turned by the sector.
                      (rx ry) (values (+ (* tc qx) (* ts qy)) (- (* tc qy) (* ts qx)))]
                  (assert.is_true (< (abs (- qx ax)) 1e-9) (.. n " sectors: x " qx " " ax))
                  (assert.is_true (< (abs (- qy (* sign ay))) 1e-9) (.. n " sectors: y " qy " " ay))
                  (assert.is_true (< (abs (- rx bx)) 1e-9) (.. n " sectors, neighbour: x " rx " " bx))
                  (assert.is_true (< (abs (- ry (* sign by))) 1e-9) (.. n " sectors, neighbour: y " ry " " by))))))
          ;; The fold is structure (another key); its lines are values (the same GLSL
          ;; for 12 and 16 sectors: two folds after the three exact ones).
          (let [key #(. (plan-of (.. "{:kind :polar :count " $ " :children [{:kind :sphere :radius 0.2 :pos [1 " $2 " 0]}]}")) :tape :key)]
            (assert.are_not.equal (key 12 0) (key 12 0.1))
            (assert.are.equal (key 12 0) (key 16 0))
            (assert.are_not.equal (key 12 0) (key 10 0))))))

    (it "bounds a mirror by its child's box and that box's image"
      (fn []
        (let [p (plan-of "{:kind :mirror :normal [0 1 0] :children [{:kind :union :pos [0 2 0] :children [{:kind :box :size [1 1 1]} {:kind :torus}]}]}")
              info (. p.tape.objects 1 :info :children 1)]
          (assert.are.equal :mirror info.kind)
          ;; The union spans x and y within 1.25 of (0 2) (the torus), z within 0.5
          ;; (the box); mirrored across y = 0. The bounds' circle about the normal
          ;; would give x within 3.48.
          (assert.are.same [-1.25 -3.25 -0.5] info.box.lo)
          (assert.are.same [1.25 3.25 0.5] info.box.hi))))))

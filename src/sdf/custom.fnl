;; Custom nodes: a scene's own distance function, {:kind :custom :distance (fn [x y z]
;; ...) :bounds [hx hy hz]}. The scene worker finds the fn's form in the parsed file
;; (by the line Lua says the closure was defined on), translates it to GLSL and Lua
;; (src/sdf/translate.fnl), measures its Lipschitz factor and sends the texts back as
;; plain data; lowering (src/sdf/lower.fnl) turns that data into a descriptor like a
;; primitive's, so every emitter, the CPU reference and the probe take it as they
;; take a sphere.

;; `pairs` under another name: a loop over `pairs` by that name is LuaJIT's ITERN,
;; which Debian 12's LuaJIT ends early once despecialised (see src/util/wire.fnl).
(local each-pair pairs)

(local fennel (require :fennel))
(local translate (require :src.sdf.translate))

(local limits
  {;; The Lipschitz estimate: central differences at the centres of a 16^3 grid over
   ;; the bounds grown by half (the far field outside is the box's, 1-Lipschitz),
   ;; and as many random points again, from a fixed seed: 57,344 calls.
   :grid 16 :random 4096 :grow 1.5
   ;; Only points outside the shape count (the slope inside limits no step), each
   ;; stencil outside it too. Then a refinement of at most :refine-ops operations
   ;; (half for the walks, half for the climbs), from at most :refine-seeds points
   ;; of each kind (the nearest the surface and the grid's dips for the walks, the
   ;; steepest for the climbs): a walk of :walk-steps steps, :bisections halvings
   ;; where it crosses the surface; a climb of :climb-steps turns of :directions
   ;; random directions each, taken on a gain of :climb-gain at least (rounding is
   ;; no gain), a step into the surface slid along it by :slide-halvings halvings;
   ;; differences down to :min-step times the bounds (finer would read rounding, or
   ;; a step's or a fract's jump, as a slope). Measured: 70,000 to 250,000 calls
   ;; here, 10 to 60 ms a function.
   :refine-ops 3e7 :refine-seeds 16 :walk-steps 40 :bisections 30
   :climb-steps 400 :directions 12 :climb-gain 1e-4 :slide-halvings 8 :min-step 1e-6
   ;; A costly function gets fewer points, so that no estimate takes more than
   ;; about this many operations (0.1 to 0.3 s here); never fewer than an 8^3 grid.
   :measure-ops 3e7 :min-grid 8
   ;; A jump: the grid's :jump-pairs neighbours (both outside) whose difference
   ;; stands out most above their line's next pairs', and the random pairs below,
   ;; are halved toward the half that differs more, up to
   ;; :jump-halvings times or below :min-step: a slope's difference halves with the
   ;; segment, a jump's stays. A difference that kept :jump-keep of itself over each
   ;; of the last :jump-run halvings, and is above :jump-least times the bounds (a
   ;; ray's overstep below that is under the marcher's hit distance), is a jump.
   ;; Random pairs too: :jump-random at each of :jump-scales distances, those whose
   ;; difference per unit passes :jump-slack times the slope measured.
   :jump-pairs 32 :jump-halvings 40 :jump-keep 0.9 :jump-run 8 :jump-least 1e-4
   :jump-random 512 :jump-scales 8 :jump-slack 1.2
   ;; And segments of :jump-across times the bounds across the steepest points.
   :jump-across 2e-3
   ;; All of it within :jump-ops operations (the halvings of 115 segments and the
   ;; random pairs take 13,000 calls of the function).
   :jump-ops 3e6
   ;; A measured factor at most this is taken as 1: central differences across a
   ;; kink of an exact distance read below 1, and rounding adds ~1e-6.
   :exact-slack 1.01
   ;; A measured factor above that is raised by this margin: the sampled maximum is
   ;; a lower bound of the true one, which may lie between two samples.
   :margin 1.1
   ;; A declared :lipschitz may be below the measured one by this much (rounding of
   ;; the differences), no more.
   :declared-slack 1.01
   ;; The bounds: each face sampled at a grid of (:face-grid + 1)^2 points (fewer
   ;; for a costly function, :bounds-ops operations at most, never under
   ;; :min-face-grid); a crossing shape's box grown by :bounds-step per axis up to
   ;; :bounds-growth times, then each axis brought back by :bounds-halvings
   ;; halvings, in :bounds-search-ops operations at most.
   :face-grid 24 :min-face-grid 8 :bounds-ops 3e6
   ;; Shapes around the box: the faces of boxes grown by :bounds-step up to
   ;; :shell-growth times, at half the grid.
   :shell-growth 4
   :bounds-step 1.25 :bounds-growth 64 :bounds-halvings 8 :bounds-search-ops 3e7
   ;; A parameter that takes a range of values (a function of time's declared
   ;; :ranges, a slider's :min and :max): the factor and the bounds are checked at
   ;; :range-points values of one such parameter (its ends and evenly between); for
   ;; several, at their corners (all of them up to :range-corners, else that many of
   ;; a fixed seed, the all-low and all-high among them), the middle, and seeded
   ;; combinations up to :range-samples in all. All the samples together take at most
   ;; :range-share times the operations of one measure (and one bounds check): each
   ;; is measured as if the function cost that much more (see measure's ?cost).
   :range-points 5 :range-corners 8 :range-samples 12 :range-share 2})

;;; Finding the form of a closure

(fn index-fn-forms [node index depth]
  ;; Every (fn ...) list within `node`, by line.
  (when (and (= (type node) :table) (< depth 200) (not (fennel.sym? node)))
    (when (and (fennel.list? node) (fennel.sym? (. node 1)) (= "fn" (tostring (. node 1))))
      (let [src (fennel.ast-source node)]
        (when (and src src.line)
          (when (not (. index src.line)) (tset index src.line []))
          (table.insert (. index src.line) node))))
    (each [k v (each-pair node)]
      (index-fn-forms k index (+ depth 1))
      (index-fn-forms v index (+ depth 1))))
  index)

;; A file's fn forms by line, built once per load (a scene of many custom nodes
;; walks its forms once).
(local indexes (setmetatable {} {:__mode :k}))

(fn fn-forms-at [forms line]
  (when (not (. indexes forms)) (tset indexes forms (index-fn-forms forms {} 0)))
  (or (. indexes forms line) []))

(fn param-count [form]
  (let [params (. form (if (fennel.sym? (. form 2)) 3 2))]
    (if (fennel.sequence? params) (length params) -1)))

(fn inside? [inner outer]
  (var found? false)
  (fn walk [node depth]
    (when (and (not found?) (= (type node) :table) (< depth 200))
      (if (rawequal node inner) (set found? true)
          (each [_ v (each-pair node)] (walk v (+ depth 1))))))
  (each [i v (ipairs outer)] (when (> i 1) (walk v 1)))
  found?)

(fn find-form [f forms file]
  "The parsed (fn ...) form among `forms` (a file's top-level forms) that closure `f`
was compiled from; or nil, why, and the reason's kind (:elsewhere, :no-form or
:shared-line)."
  (let [info (debug.getinfo f :Su)]
    (if (not= info.source (.. "@" file))
        (values nil "must be written in the scene file itself as (fn [x y z] ...)" :elsewhere)
        (let [found (fn-forms-at forms info.linedefined)
              same-arity (icollect [_ form (ipairs found)]
                           (when (or (= nil info.nparams) (= info.nparams (param-count form))) form))
              outermost (icollect [_ a (ipairs same-arity)]
                          (when (not (accumulate [in? false _ b (ipairs same-arity)]
                                       (or in? (and (not (rawequal a b)) (inside? a b)))))
                            a))
              ;; The same form may be reached twice (a key and a value): one each.
              unique (let [seen {}]
                       (icollect [_ form (ipairs outermost)]
                         (when (not (. seen form)) (tset seen form true) form)))]
          (case (length unique)
            1 (. unique 1)
            0 (values nil "must be written (fn [x y z] ...) in the scene file (a #(...) has no form to translate)" :no-form)
            _ (values nil (.. "line " info.linedefined " holds several functions with "
                              (or info.nparams "as many") " parameters; put the distance function on a line of its own")
                      :shared-line))))))

;; Why a function of the file the distance function calls cannot be translated, by
;; find-form's kind of reason (its own words speak of the distance function).
(fn unreadable [kind name]
  (case kind
    :elsewhere "it is not written in the scene file"
    :no-form (.. "it has no (fn ...) form in the scene file (a #(...) has none); write it (fn "
                 name " [a b] ...)")
    _ "its line holds another function with as many parameters; put it on a line of its own"))

(fn lua-name [name]
  "The Lua name Fennel gives a local named `name` (fennel.mangle is a global's
name): a Lua keyword or a leading digit gets _ before it; - becomes _, any other
character not a letter, digit or _ becomes _XX, its hex code: sd-box is sd_box. A
local that would reuse a name in scope gets a number after it (a second (local r
...) is r0)."
  (let [raw (if (or (name:match "^%d")
                    (. {:and true :break true :do true :else true :elseif true :end true
                        :false true :for true :function true :goto true :if true :in true
                        :local true :nil true :not true :or true :repeat true :return true
                        :then true :true true :until true :while true}
                       name))
                (.. "_" name)
                name)
        (mangled) (: (raw:gsub "-" "_") :gsub "[^%w_]" #(string.format "_%02x" ($:byte)))]
    mangled))

(fn upvalue-of [f name]
  "The value of `f`'s upvalue for the scene's name `name` (found? and the value): the
one named as Fennel mangles `name`, else the only one named so with a number after
it (Fennel's name for a local that shadows another of the same name)."
  (let [base (lua-name name)
        exact []
        numbered []]
    (var i 1)
    (while (debug.getupvalue f i)
      (let [(upname value) (debug.getupvalue f i)]
        (if (= upname base) (table.insert exact [value])
            (and (= (upname:sub 1 (length base)) base) (: (upname:sub (+ 1 (length base))) :match "^%d+$"))
            (table.insert numbered [value])))
      (set i (+ i 1)))
    (if (= 1 (length exact)) (values true (. exact 1 1))
        (and (= 0 (length exact)) (= 1 (length numbered))) (values true (. numbered 1 1))
        false)))

(fn resolver [f forms file]
  "A resolver for translate: names the closure `f` reaches outside itself (its
upvalues), as numbers, math functions and functions of the file (`forms`, `file`)."
  (let [math-names (collect [k v (each-pair math)] (when (= (type v) :function) (values v k)))]
    ;; LuaJIT's math.mod is an alias of fmod: call the function by its own name.
    (when math.fmod (tset math-names math.fmod :fmod))
    (fn [name]
      (let [(found? value) (upvalue-of f name)]
        (when found?
          (case (type value)
            :number {:number value}
            :nil {:nil true}
            ;; An array of numbers or vectors (translate checks its items).
            :table {:table value}
            ;; The name as written when it is math's own (local {: mod} math).
            :function (if (and (= (. math name) value) (. math-names value)) {:math name}
                          (. math-names value) {:math (. math-names value)}
                          (case (find-form value forms file)
                            form {:helper form :resolve (resolver value forms file)}
                            (_ _ kind) {:unreadable (unreadable kind name)}))
            t {:other (.. "a " t)}))))))

;;; Hashing, for the shader's structure key

(fn digest [text]
  "A short hex digest of `text` (two polynomial hashes modulo a prime below 2^32,
exact in doubles) and its length: equal texts, equal digests."
  (let [p 4294967291]
    (var a 0)
    (var b 7)
    (for [i 1 (length text)]
      (let [c (text:byte i)]
        (set a (% (+ (* a 31) c) p))
        (set b (% (+ (* b 131) c) p))))
    (string.format "%08x%08x-%d" a b (length text))))

;;; The Lipschitz factor

(fn lcg [seed]
  (var s seed)
  (fn []
    (set s (% (+ (* s 1103515245) 12345) 2147483648))
    (/ s 2147483648)))

(fn finite-number? [v]
  (and (= v v) (< (math.abs v) math.huge)))

;; The measure's state, one table `m` passed along: the function and its arguments,
;; the grown bounds (hx hy hz), the steps (h0, the differences' first; hmin, their
;; least), the calls made and allowed (evaluations, phase-end), the steepest slope
;; found and where (worst, at), the first point of a value that is not a number
;; (bad), the seeds of the refinement (steep, near, dips) and the random source.

(fn evaluate [m x y z]
  (set m.evaluations (+ m.evaluations 1))
  (let [v (m.cpu x y z (m.unpack m.args))]
    (when (and (not m.bad) (not (finite-number? v))) (set m.bad [x y z]))
    v))

(fn within? [m x y z]
  (and (<= (math.abs x) m.hx) (<= (math.abs y) m.hy) (<= (math.abs z) m.hz)))

(fn slope [m x y z h]
  ;; The central differences' gradient at a point outside (value > 0), its length
  ;; and components; the step is halved while the stencil reaches inside (the slope
  ;; in there limits no step), up to 4 times; nil if it still does. The steepest
  ;; is kept in m.worst, its point in m.at.
  (var (g gx gy gz) nil)
  (var step h)
  (for [_ 1 5 &until (or g m.bad)]
    (let [xp (evaluate m (+ x step) y z) xm (evaluate m (- x step) y z)
          yp (evaluate m x (+ y step) z) ym (evaluate m x (- y step) z)
          zp (evaluate m x y (+ z step)) zm (evaluate m x y (- z step))]
      (if (and (> xp 0) (> xm 0) (> yp 0) (> ym 0) (> zp 0) (> zm 0))
          (do (set gx (/ (- xp xm) (* 2 step)))
              (set gy (/ (- yp ym) (* 2 step)))
              (set gz (/ (- zp zm) (* 2 step)))
              (set g (math.sqrt (+ (* gx gx) (* gy gy) (* gz gz)))))
          (set step (* 0.5 step)))))
  (when (and g (not m.bad) (not (finite-number? g))) (set m.bad [x y z]))
  (when (and g (not m.bad) (> g m.worst)) (set m.worst g) (set m.at [x y z]))
  (values g gx gy gz))

(fn keep! [list key item seeds]
  ;; `item` into `list`, kept sorted by `key` (least first), at most `seeds` long.
  (when (or (< (length list) seeds) (< key (. list (length list) :key)))
    (set item.key key)
    (var i (length list))
    (while (and (> i 0) (> (. list i :key) key)) (set i (- i 1)))
    (table.insert list (+ i 1) item)
    (when (> (length list) seeds) (table.remove list))))

(fn sample [m x y z]
  ;; The value at a point; where it is outside, its slope, and the point kept
  ;; among the steepest and among those nearest the surface (value over slope).
  (when (not m.bad)
    (let [v (evaluate m x y z)]
      (when (and (not m.bad) (> v 0))
        (let [g (slope m x y z m.h0)]
          (when (and g (not m.bad))
            (keep! m.steep (- g) {: x : y : z : v : g} m.seeds)
            (keep! m.near (/ v (math.max g 1e-12)) {: x : y : z : v : g} m.seeds))))
      v)))

(fn grid-coord [m i half]
  (* half (- (/ (* 2 (+ i 0.5)) m.n) 1)))

(fn sample-grid [m]
  ;; The samples at the centres of an n^3 grid: their values, i + n j + n^2 k + 1.
  (let [n m.n
        grid []]
    (for [i 0 (- n 1)]
      (for [j 0 (- n 1)]
        (for [k 0 (- n 1)]
          (tset grid (+ 1 i (* n j) (* n n k))
                (or (sample m (grid-coord m i m.hx) (grid-coord m j m.hy) (grid-coord m k m.hz)) 0)))))
    grid))

(fn grid-dips [m grid]
  ;; A positive value below all its grid neighbours': the field dips toward a
  ;; surface that no sample saw (an exact distance has no such dip outside).
  (let [n m.n
        dips []]
    (when (not m.bad)
      (for [i 0 (- n 1)]
        (for [j 0 (- n 1)]
          (for [k 0 (- n 1)]
            (let [v (. grid (+ 1 i (* n j) (* n n k)))]
              (when (and (> v 0)
                         (accumulate [low? true _ [di dj dk] (ipairs [[-1 0 0] [1 0 0] [0 -1 0] [0 1 0] [0 0 -1] [0 0 1]])]
                           (let [a (+ i di) b (+ j dj) c (+ k dk)]
                             (and low? (or (< a 0) (>= a n) (< b 0) (>= b n) (< c 0) (>= c n)
                                           (<= v (. grid (+ 1 a (* n b) (* n n c)))))))))
                (keep! dips v {:x (grid-coord m i m.hx) :y (grid-coord m j m.hy) :z (grid-coord m k m.hz) : v}
                       m.seeds)))))))
    dips))

(fn spent? [m] (or m.bad (>= m.evaluations m.phase-end)))

(fn random-point [m]
  ;; A random point of the grown bounds.
  (values (* m.hx (- (* 2 (m.rand)) 1)) (* m.hy (- (* 2 (m.rand)) 1)) (* m.hz (- (* 2 (m.rand)) 1))))

(fn random-direction [m]
  ;; A random unit vector.
  (let [a (* 2 math.pi (m.rand)) u (- (* 2 (m.rand)) 1) s (math.sqrt (- 1 (* u u)))]
    (values (* s (math.cos a)) (* s (math.sin a)) u)))

(fn directions [m]
  ;; limits.directions random unit vectors (a thin valley of the slope is followed
  ;; by the one nearest its way).
  (fcollect [_ 1 limits.directions] [(random-direction m)]))

(fn outside-toward [m x y z cx cy cz]
  ;; The point (cx cy cz) when it is outside and within the grown bounds; else the
  ;; last point outside on the way to it from (x y z), by halvings (so that a step
  ;; into the surface slides along it), and the bracket's length; nil when none is.
  (when (and (within? m cx cy cz) (not (spent? m)))
    (if (> (evaluate m cx cy cz) 0) (values cx cy cz)
        (do (var (ox oy oz) (values x y z))
            (var (ix iy iz) (values cx cy cz))
            (for [_ 1 limits.slide-halvings &until (spent? m)]
              (let [mx (* 0.5 (+ ox ix)) my (* 0.5 (+ oy iy)) mz (* 0.5 (+ oz iz))]
                (if (> (evaluate m mx my mz) 0) (set (ox oy oz) (values mx my mz))
                    (set (ix iy iz) (values mx my mz)))))
            (when (not (and (= ox x) (= oy y) (= oz z)))
              ;; Within the bracket's length of the surface: the step's most.
              (values ox oy oz (math.max (math.abs (- ix ox)) (math.abs (- iy oy)) (math.abs (- iz oz)))))))))

(fn climb [m s]
  ;; From a steep point, steps of a shrinking size toward a steeper one outside,
  ;; the differences' step a quarter of the climb's.
  (var (x y z g) (values s.x s.y s.z s.g))
  (local r0 (/ m.scale m.n))
  (var r r0)
  (var turns 0)
  (while (and (not (spent? m)) (> r (* 4 m.hmin)) (< turns limits.climb-steps))
    (set turns (+ turns 1))
    (let [h (math.max m.hmin (math.min m.h0 (* 0.25 r)))]
      (var best nil)
      (each [_ [ux uy uz] (ipairs (directions m))]
        (let [(cx cy cz near) (outside-toward m x y z (+ x (* r ux)) (+ y (* r uy)) (+ z (* r uz)))]
          (when (and cx (not (spent? m)))
            (let [cg (slope m cx cy cz (math.max m.hmin (math.min h (or near h))))]
              (when (and cg (> cg (* (or (?. best 4) g) (+ 1 limits.climb-gain))))
                (set best [cx cy cz cg]))))))
      (if best
          (do (set (x y z g) (m.unpack best))
              (set r (math.min r0 (* 2 r))))
          (do (set r (* 0.5 r))
              ;; The point's own slope at the finer step.
              (set g (or (slope m x y z (math.max m.hmin (math.min m.h0 (* 0.25 r)))) g)))))))

(fn bisect! [m x y z cx cy cz]
  ;; Between a point outside (x y z) and one inside (cx cy cz): halvings, each point
  ;; outside sampled with a step a quarter of the bracket's.
  (var (ox oy oz) (values x y z))
  (var (ix iy iz) (values cx cy cz))
  (for [_ 1 limits.bisections &until (spent? m)]
    (let [mx (* 0.5 (+ ox ix)) my (* 0.5 (+ oy iy)) mz (* 0.5 (+ oz iz))
          mv (evaluate m mx my mz)
          span (math.sqrt (+ (* (- ix ox) (- ix ox)) (* (- iy oy) (- iy oy))
                             (* (- iz oz) (- iz oz))))]
      (if (> mv 0)
          (do (slope m mx my mz (math.max m.hmin (math.min m.h0 (* 0.25 span))))
              (set (ox oy oz) (values mx my mz)))
          (set (ix iy iz) (values mx my mz))))))

(fn walk [m s]
  ;; Down the field by its value over its slope, halved until the value falls;
  ;; where it crosses the surface, a bisection (bisect!).
  (var (x y z v) (values s.x s.y s.z s.v))
  (var h m.h0)
  (var done? false)
  (for [_ 1 limits.walk-steps &until (or done? (spent? m))]
    (let [(g gx gy gz) (slope m x y z h)]
      (if (or (not g) (< g 1e-9))
          (set done? true)
          (let [ux (/ (- gx) g) uy (/ (- gy) g) uz (/ (- gz) g)]
            (var len (/ v g))
            (var found nil)
            (for [_ 1 24 &until (or found (spent? m) (< len m.hmin))]
              (let [nx (+ x (* len ux)) ny (+ y (* len uy)) nz (+ z (* len uz))
                    nv (when (within? m nx ny nz) (evaluate m nx ny nz))]
                (if (and nv (< nv v)) (set found [nx ny nz nv]) (set len (* 0.5 len)))))
            (case found
              nil (set done? true)
              [nx ny nz nv]
              (if (> nv 0)
                  (do (set (x y z v) (values nx ny nz nv))
                      (set h (math.max m.hmin (math.min m.h0 (* 0.25 (/ nv g))))))
                  (do (bisect! m x y z nx ny nz)
                      (set done? true)))))))))

;; Jumps: a distance that is not continuous outside the shape lets a ray step by
;; the larger side's value across the jump, past a surface; no factor covers it.

(fn pair-jump [m ax ay az av bx by bz bv]
  ;; Halvings of the segment between two points outside, each toward the half whose
  ;; ends differ more (see limits.jump-*). A jump: {:size :at :low :high}. A slope
  ;; (the difference halved with the segment): nil, the slope at the bracket's
  ;; middle kept by `slope`. Nil too where a halving reaches inside the shape (a
  ;; jump at the surface moves the hit, no step past it).
  (var (ax ay az av bx by bz bv) (values ax ay az av bx by bz bv))
  (var len (math.sqrt (+ (* (- bx ax) (- bx ax)) (* (- by ay) (- by ay)) (* (- bz az) (- bz az)))))
  (var (run inside? turns) (values 0 false 0))
  (while (and (not inside?) (not (spent? m)) (< turns limits.jump-halvings) (> len m.hmin))
    (set turns (+ turns 1))
    (let [before (math.abs (- av bv))
          mx (* 0.5 (+ ax bx)) my (* 0.5 (+ ay by)) mz (* 0.5 (+ az bz))
          mv (evaluate m mx my mz)]
      (if (not (> mv 0)) (set inside? true)
          (>= (math.abs (- av mv)) (math.abs (- mv bv)))
          (set (bx by bz bv) (values mx my mz mv))
          (set (ax ay az av) (values mx my mz mv)))
      (set len (* 0.5 len))
      (set run (if (>= (math.abs (- av bv)) (* limits.jump-keep before)) (+ run 1) 0))))
  (let [size (math.abs (- av bv))
        mx (* 0.5 (+ ax bx)) my (* 0.5 (+ ay by)) mz (* 0.5 (+ az bz))]
    (if (or inside? m.bad) nil
        (and (>= run limits.jump-run) (> size (* limits.jump-least m.scale)))
        {: size :at [mx my mz] :low (math.min av bv) :high (math.max av bv)}
        (do (slope m mx my mz (math.max m.hmin len)) nil))))

(fn grid-pairs [m grid pairs]
  ;; Into `pairs`: the limits.jump-pairs pairs of the grid's neighbours, both
  ;; outside, whose difference stands out most above those of the pairs before and
  ;; after them on the same line (a slope's differences change little from one pair
  ;; to the next; a jump's pair carries the jump beside them).
  (let [n m.n
        found []]
    (fn at [i j k]
      (when (and (>= i 0) (< i n) (>= j 0) (< j n) (>= k 0) (< k n))
        (let [v (. grid (+ 1 i (* n j) (* n n k)))]
          (when (> v 0) v))))
    (fn difference [i j k di dj dk]
      (let [v (at i j k) w (at (+ i di) (+ j dj) (+ k dk))]
        (if (and v w) (math.abs (- v w)) 0)))
    (for [i 0 (- n 1)]
      (for [j 0 (- n 1)]
        (for [k 0 (- n 1)]
          (each [_ [di dj dk] (ipairs [[1 0 0] [0 1 0] [0 0 1]])]
            (let [v (at i j k) w (at (+ i di) (+ j dj) (+ k dk))]
              (when (and v w)
                (let [excess (- (math.abs (- v w))
                                (math.max (difference (- i di) (- j dj) (- k dk) di dj dk)
                                          (difference (+ i di) (+ j dj) (+ k dk) di dj dk)))]
                  (when (> excess 0)
                    (keep! found (- excess)
                           {:a [(grid-coord m i m.hx) (grid-coord m j m.hy) (grid-coord m k m.hz) v]
                            :b [(grid-coord m (+ i di) m.hx) (grid-coord m (+ j dj) m.hy) (grid-coord m (+ k dk) m.hz) w]}
                           limits.jump-pairs)))))))))
    (each [_ p (ipairs found)] (table.insert pairs p))))

(fn random-pairs [m pairs]
  ;; Into `pairs`: the limits.jump-pairs pairs of random points outside, at
  ;; distances from a quarter of the bounds' largest half extent down by halvings
  ;; (limits.jump-scales of them, limits.jump-random pairs each, fewer for a costly
  ;; function), whose difference per unit passes the slope measured so far by
  ;; limits.jump-slack: a jump that the grid's pairs do not single out (its
  ;; difference beside a slope's over the grid's step) passes a slope of 1 over
  ;; a distance below its size.
  (let [count (math.max 1 (math.floor (* limits.jump-random (/ (^ m.n 3) (^ limits.grid 3)))))
        least (* limits.jump-slack (math.max 1 m.worst))
        found []]
    (for [k 2 (+ 1 limits.jump-scales) &until (spent? m)]
      (let [d (/ m.scale (^ 2 k))]
        (for [_ 1 count &until (spent? m)]
          (let [(x y z) (random-point m)
                (ux uy uz) (random-direction m)
                bx (+ x (* d ux)) by (+ y (* d uy)) bz (+ z (* d uz))]
            (when (within? m bx by bz)
              (let [v (evaluate m x y z)
                    w (when (> v 0) (evaluate m bx by bz))
                    q (when (and w (> w 0)) (/ (math.abs (- v w)) d))]
                (when (and q (> q least))
                  (keep! found (- q) {:a [x y z v] :b [bx by bz w]} limits.jump-pairs))))))))
    (each [_ p (ipairs found)] (table.insert pairs p))))

(fn steep-pairs [m pairs]
  ;; Into `pairs`: a segment along each axis across the steepest point found and
  ;; the steepest samples, limits.jump-across times the bounds long (past the
  ;; differences' steps): a jump that a stencil straddled reads as a slope of its
  ;; size over the step, which would raise the factor by thousands instead.
  (let [r (* 0.5 limits.jump-across m.scale)]
    (each [_ [x y z] (ipairs (doto (icollect [_ s (ipairs m.steep)] [s.x s.y s.z]) (table.insert 1 m.at)))]
      (each [_ [ux uy uz] (ipairs [[r 0 0] [0 r 0] [0 0 r]])]
        (let [ax (- x ux) ay (- y uy) az (- z uz) bx (+ x ux) by (+ y uy) bz (+ z uz)]
          (when (and (within? m ax ay az) (within? m bx by bz) (not (spent? m)))
            (let [v (evaluate m ax ay az) w (evaluate m bx by bz)]
              (when (and (> v 0) (> w 0))
                (table.insert pairs {:a [ax ay az v] :b [bx by bz w]})))))))))

(fn largest-jump [m pairs]
  ;; The largest jump (pair-jump) between the ends of `pairs`, or nil.
  (accumulate [worst nil _ {:a [ax ay az av] :b [bx by bz bv]} (ipairs pairs) &until (spent? m)]
    (let [found (pair-jump m ax ay az av bx by bz bv)]
      (if (and found (or (= worst nil) (> found.size worst.size))) found worst))))

(fn find-jump [m grid]
  ;; The largest jump across the steepest points (steep-pairs), else between the
  ;; grid's pairs and the random ones (grid-pairs, random-pairs); nil when none.
  (let [steep [] others []]
    (steep-pairs m steep)
    (or (largest-jump m steep)
        (do (grid-pairs m grid others)
            (random-pairs m others)
            (largest-jump m others)))))

(fn measure [cpu bounds args ?cost]
  "The largest gradient length of `cpu` (fn [x y z ...args]) outside its shape (where
it is positive: only there does the factor limit a ray's step) within `bounds` (half
extents) grown by limits.grow, and the point; or nil, a message and the point where
it is not finite. Central differences at a grid's centres and random points, then
refined: a climb of the slope from the steepest samples, and a walk to the surface
from the samples nearest it and from the grid's positive local minima (a thin
feature between the samples), with steps small beside the feature; then the
search for a jump between the grid's neighbours (see limits.jump-*). `?cost`:
operations per call, to take fewer points for a costly function (see
limits.measure-ops and limits.refine-ops). Its third value: the calls it made;
its fourth: the largest jump found outside the shape, {:size :at :low :high}, or
nil."
  (let [[hx hy hz] (icollect [_ b (ipairs bounds)] (* b limits.grow))
        scale (math.max hx hy hz)
        cost (math.max 1 (or ?cost 1))
        full (+ (^ limits.grid 3) limits.random)
        points (math.min full (/ limits.measure-ops (* 7 cost)))
        n (math.max limits.min-grid
                    (math.min limits.grid (math.floor (^ (* 0.5 points) (/ 1 3)))))
        m {: cpu : args :unpack (or table.unpack _G.unpack) : hx : hy : hz : scale : n
           :h0 (* 1e-4 scale) :hmin (* limits.min-step scale)
           :evaluations 0 :phase-end math.huge :worst 0 :at [0 0 0] :bad nil
           :steep [] :near [] :seeds limits.refine-seeds :rand (lcg 12345)}
        grid (sample-grid m)]
    (for [_ 1 (math.floor (* limits.random (/ (^ n 3) (^ limits.grid 3))))]
      (sample m (random-point m)))
    (let [budget (+ m.evaluations (/ limits.refine-ops cost))
          dips (grid-dips m grid)]
      ;; The walks take half the refinement's evaluations at most, the climbs the rest.
      (set m.phase-end (+ m.evaluations (* 0.5 (- budget m.evaluations))))
      (each [_ s (ipairs dips)] (when (not (spent? m)) (walk m s)))
      (each [_ s (ipairs m.near)] (when (not (spent? m)) (walk m s)))
      (set m.phase-end budget)
      (each [_ s (ipairs m.steep)] (when (not (spent? m)) (climb m s)))
      ;; The jumps get their own evaluations (13,000 at most, :jump-ops operations
      ;; at most): a refinement that spent its budget must not hide one.
      (set m.phase-end (+ m.evaluations
                          (math.min (/ limits.jump-ops cost)
                                    (+ (* (+ (* 3 (+ 1 limits.refine-seeds)) (* 2 limits.jump-pairs))
                                          (+ 2 limits.jump-halvings))
                                       (* 2 limits.jump-scales limits.jump-random)))))
      (set m.jump (find-jump m grid)))
    (if m.bad (values nil "gives a value that is not a finite number" m.bad)
        (values m.worst m.at m.evaluations m.jump))))

;;; The bounds: the renderer takes the box's distance outside it

(fn face-points [[hx hy hz] m visit]
  ;; Calls (visit x y z) at an (m+1)^2 grid of each of the six faces of the box of
  ;; half extents hx hy hz, edges and corners included.
  (each [_ [a b c] (ipairs [[1 2 3] [2 3 1] [3 1 2]])]
    (let [h [hx hy hz]]
      (each [_ side (ipairs [1 -1])]
        (for [i 0 m]
          (for [j 0 m]
            (let [p []]
              (tset p a (* side (. h a)))
              (tset p b (* (. h b) (- (/ (* 2 i) m) 1)))
              (tset p c (* (. h c) (- (/ (* 2 j) m) 1)))
              (visit (. p 1) (. p 2) (. p 3)))))))))

(fn lowest-on-faces [d box m tolerance]
  ;; The lowest value of `d` on the faces of `box` (values that are not numbers
  ;; left to the measure, which refuses them), its point, the lowest on each axis's
  ;; pair of faces, and how far along each axis a point below -`tolerance` lies.
  (var (low at) (values math.huge nil))
  (local per-axis [math.huge math.huge math.huge])
  (local reach [0 0 0])
  (face-points box m
               (fn [x y z]
                 (let [v (d x y z)
                       [hx hy] box
                       axis (if (= (math.abs x) hx) 1 (= (math.abs y) hy) 2 3)]
                   (when (= v v)
                     (when (< v low) (set low v) (set at [x y z]))
                     (when (< v (. per-axis axis)) (tset per-axis axis v))
                     (when (< v (- tolerance))
                       (each [i c (ipairs [x y z])]
                         (tset reach i (math.max (. reach i) (math.abs c)))))))))
  (values low at per-axis reach))

(fn round-up [v]
  ;; `v` rounded up to two significant digits.
  (let [unit (^ 10 (- (math.floor (math.log10 v)) 1))]
    (* unit (math.ceil (- (/ v unit) 1e-9)))))

(fn check-bounds [cpu bounds args ?cost]
  "Nil when `cpu` (fn [x y z ...args]) is positive (or zero: a touch, within
rounding) on the faces of the box of half extents `bounds` and on those of boxes
limits.bounds-step, limits.bounds-step^2 ... up to limits.shell-growth times as
large, at half the grid (a shape around the box, a torus about a box in its hole,
touches none of its faces); else the lowest
value found, its point, whether that point is on the box's own faces, and a box
that holds the shape (nil when none up to limits.bounds-growth times as large is
found; then a fifth value, true when the search stopped at its budget instead): the renderer takes the box's distance outside it, so a shape that crosses
its box is cut. Each face is sampled at a grid of limits.face-grid^2 points (fewer
for a costly function, see limits.bounds-ops); the search takes at most
limits.bounds-search-ops operations."
  (let [unpack (or table.unpack _G.unpack)
        cost (math.max 1 (or ?cost 1))
        m (math.max limits.min-face-grid
                    (math.min limits.face-grid
                              (math.floor (- (math.sqrt (/ limits.bounds-ops (* 6 cost))) 1))))
        largest (math.max (unpack bounds))
        tolerance (* 1e-9 largest)
        d (fn [x y z] (cpu x y z (unpack args)))
        scaled (fn [s] (icollect [_ b (ipairs bounds)] (* s b)))]
    (var searches (math.floor (/ limits.bounds-search-ops (* cost 6 (^ (+ m 1) 2)))))
    (fn lowest [box]
      (set searches (- searches 1))
      (lowest-on-faces d box m tolerance))
    ;; The shape's farthest points below zero seen so far, per axis.
    (local reach [0 0 0])
    (fn reached! [r] (each [i v (ipairs r)] (tset reach i (math.max (. reach i) v))))
    (var (low at on-face? box) (let [(l a _ r) (lowest bounds)] (reached! r) (values l a true nil)))
    ;; The shells beyond the box.
    (var s 1)
    (while (and (>= low (- tolerance)) (<= (* s limits.bounds-step) limits.shell-growth))
      (set s (* s limits.bounds-step))
      (let [(l a _ r) (lowest-on-faces d (scaled s) (math.ceil (* 0.5 m)) tolerance)]
        (reached! r)
        (when (< l (- tolerance))
          (set (low at on-face? box) (values l a false (scaled s))))))
    (when (< low (- tolerance))
      ;; Grown by limits.bounds-step on each axis whose faces the shape crosses,
      ;; then each axis brought back by halvings while the faces stay positive and
      ;; the box holds every point found inside the shape.
      (set box (or box (icollect [_ b (ipairs bounds)] b)))
      (var found? false)
      (while (and (not found?) (> searches 0)
                  (<= (/ (math.max (unpack box)) largest) limits.bounds-growth))
        (let [(_ _ per-axis r) (lowest box)]
          (reached! r)
          (if (accumulate [ok? true _ v (ipairs per-axis)] (and ok? (>= v (- tolerance))))
              (set found? true)
              (each [i v (ipairs per-axis)]
                (when (< v (- tolerance)) (tset box i (* (. box i) limits.bounds-step)))))))
      (fn holds? [b]
        (and (accumulate [ok? true i v (ipairs b)] (and ok? (>= v (. reach i))))
             (let [(l _ _ r) (lowest b)] (reached! r) (>= l (- tolerance)))))
      (when found?
        (for [i 1 3]
          (var (lo hi) (values (math.max (. bounds i) (. reach i)) (. box i)))
          (for [_ 1 limits.bounds-halvings &until (<= searches 0)]
            (let [mid (* 0.5 (+ lo hi))
                  b (icollect [k v (ipairs box)] (if (= k i) mid v))]
              (if (holds? b) (set hi mid) (set lo mid))))
          (tset box i hi))
        ;; Rounded up to two digits, when that box holds it too.
        (let [rounded (icollect [_ v (ipairs box)] (round-up v))]
          (when (holds? rounded) (set box rounded))))
      ;; Without a box, whether the search stopped at its budget (a costly
      ;; function) rather than at limits.bounds-growth.
      (values low at on-face? (when found? box) (and (not found?) (<= searches 0))))))

(fn point-text [p]
  (string.format "[%.3g %.3g %.3g]" (. p 1) (. p 2) (. p 3)))

(fn factor [measured ?declared at ?trusted?]
  "The factor the distance is divided by, from the `measured` gradient and the
`?declared` :lipschitz; or nil and why the declaration is refused. A declaration
below the measure is refused unless `?trusted?` (the node's :trust-lipschitz):
then it is used as declared."
  (if ?declared
      (if (and (> measured (* ?declared limits.declared-slack)) (not ?trusted?))
          (values nil (string.format "declares %g, but the distance changes by %.3g per unit at %s (sampled outside the shape, over its bounds); declare at least %.3g, leave :lipschitz out to have it measured, or add :trust-lipschitz true to use %g anyway (a ray may then step past the surface)"
                                     ?declared measured (point-text at) measured ?declared))
          ?declared)
      (<= measured limits.exact-slack) 1
      (* measured limits.margin)))

;;; Parameters that take a range of values

(fn range-samples [names given ranges]
  "The parameters' values to check a custom node at: a list of {:args :at}, :args the
arguments after x y z (in the order of `names`, the fn's parameters, from `given`
by name, but for those with a range in `ranges` {name [lo hi]}) and :at the ranged
ones' values by name. One sample of `values` when no parameter has a range; see
limits.range-points, range-corners and range-samples for the others."
  (let [ranged (icollect [_ n (ipairs names)] (when (. ranges n) n))
        m (length ranged)
        rand (lcg 4242)
        points []
        seen {}]
    (fn add! [at]
      ;; `at`: a value per ranged name, in the order of `ranged`.
      (let [key (table.concat (icollect [_ v (ipairs at)] (string.format "%.17g" v)) " ")]
        (when (not (. seen key))
          (tset seen key true)
          (table.insert points at))))
    (fn at-fraction [i f]
      (let [[lo hi] (. ranges (. ranged i))]
        (if (>= f 1) hi (<= f 0) lo (+ lo (* f (- hi lo))))))
    (if (= m 1)
        (for [k 0 (- limits.range-points 1)]
          (add! [(at-fraction 1 (/ k (- limits.range-points 1)))]))
        (> m 1)
        (do (if (<= (^ 2 m) limits.range-corners)
                (for [c 0 (- (^ 2 m) 1)]
                  (add! (fcollect [i 1 m] (at-fraction i (% (math.floor (/ c (^ 2 (- i 1)))) 2)))))
                (do (add! (fcollect [i 1 m] (at-fraction i 0)))
                    (add! (fcollect [i 1 m] (at-fraction i 1)))
                    (for [_ 3 limits.range-corners]
                      (add! (fcollect [i 1 m] (at-fraction i (if (< (rand) 0.5) 0 1)))))))
            (add! (fcollect [i 1 m] (at-fraction i 0.5)))
            (for [_ 1 (* 4 limits.range-samples) &until (>= (length points) limits.range-samples)]
              (add! (fcollect [i 1 m] (at-fraction i (rand)))))))
    (if (= m 0)
        [{:args (icollect [_ n (ipairs names)] (. given n)) :at {}}]
        (icollect [_ at (ipairs points)]
          (let [by-name (collect [i n (ipairs ranged)] n (. at i))]
            {:args (icollect [_ n (ipairs names)] (or (. by-name n) (. given n)))
             :at by-name})))))

(fn sample-cost [cost n]
  "The cost per call to give measure and check-bounds for each of `n` samples of a
function of `cost` operations per call: all of them together take about
limits.range-share times one measure's operations."
  (* (math.max 1 (or cost 1)) (math.max 1 (/ n limits.range-share))))

;;; The worker's side: from a closure to plain data

(fn capture [f forms file]
  "Translate the distance closure `f` of scene `file` (whose parsed top-level forms
are `forms`): {:glsl :lua :glsl-name :params :cost}, or nil, a message and a line."
  (case (find-form f forms file)
    (nil msg) (values nil msg (. (debug.getinfo f :S) :linedefined))
    form (translate.translate form {:resolve (resolver f forms file)})))

;;; The main process's check of the texts: they come from the worker, which runs the
;;; scene's code. What the translator writes is a small language; anything else (a
;;; string, a table, a global, a loop past the translator's limits, a recursive call)
;;; is refused before `load` or the shader compiler sees it.

(local lua-words
  ;; break: an early end of a for loop (&until, a stop of (math.min n K)), which
  ;; only shortens a bounded loop.
  (collect [_ w (ipairs ["local" "function" "return" "end" "if" "then" "else" "for" "do" "and"
                         "or" "not" "math" "break"])]
    w true))
(local lua-math
  (collect [_ w (ipairs ["sqrt" "abs" "floor" "ceil" "sin" "cos" "tan" "asin" "acos" "atan"
                         "atan2" "exp" "log" "min" "max"])]
    w true))
(local glsl-words
  (collect [_ w (ipairs ["float" "vec2" "vec3" "vec4" "int" "bool" "return" "if" "else" "for" "break"
                         "p" "sqrt" "abs" "floor" "ceil" "sin" "cos" "tan" "asin" "acos" "atan"
                         "exp" "log" "pow" "min" "max" "mod" "length" "sign"])]
    w true))
(local swizzles {:x true :y true :z true :w true})

(fn tokens [text]
  "The tokens of `text` (names, numbers, operators), or nil at a character the
translator never writes."
  (let [out []
        n (length text)]
    (var i 1)
    (var bad? false)
    (while (and (<= i n) (not bad?))
      (let [ws (text:match "^%s+" i)]
        (if ws (set i (+ i (length ws)))
            (let [tok (or (text:match "^[%a_][%w_]*" i)
                          (text:match "^%d+%.?%d*[eE][-+]?%d+" i)
                          (text:match "^%d+%.?%d*" i)
                          (text:match "^[=~<>!]=" i)
                          (text:match "^&&" i) (text:match "^||" i) (text:match "^%+%+" i)
                          (text:match "^%+=" i)
                          (text:match "^[-+*/%%^(),=<>.;{}?:!]" i))]
              (if tok (do (table.insert out tok) (set i (+ i (length tok))))
                  (set bad? true))))))
    (when (not bad?) out)))

(fn number? [tok] (not= nil (tok:match "^%d")))

(fn signed [toks k]
  ;; The whole number at token k ("-" then digits, or digits) and the index after it.
  (if (= (. toks k) "-")
      (values (and (. toks (+ k 1)) (tonumber (. toks (+ k 1))) (- (tonumber (. toks (+ k 1)))))
              (+ k 2))
      (values (and (. toks k) (tonumber (. toks k))) (+ k 1))))

(fn loop-turns [start stop step]
  ;; The turns of a loop of whole bounds and step, its counter within
  ;; translate.limits.loop-bound (past it, GLSL's int overflows and its float loses
  ;; whole numbers: see translate); nil for any other loop.
  (let [a (tonumber start) b (tonumber stop) c (tonumber step)
        bound translate.limits.loop-bound
        whole? #(and $ (= $ (math.floor $)) (<= (math.abs $) bound))]
    (when (and (whole? a) (whole? b) (whole? c) (not= c 0))
      (let [turns (math.max 0 (+ 1 (math.floor (/ (- b a) c))))
            past (+ a (* c turns))]
        (when (<= (math.abs past) bound) turns)))))

(fn check-lua [text]
  "True when `text` is Lua of the translator's kind: generated names, math's
functions, for loops of constant bounds within translate's limits, calls of helpers
defined before (no recursion).
No value is ever a function but where it is called: a helper's name is defined once
and otherwise only called, math's functions only called, and a variable never
called. So the helpers' calls go from each to ones defined before it, and with every
loop bounded, the text ends: a helper redefined under its own name (which its body
would then call), or one passed to itself as a value, is refused."
  (case (tokens text)
    nil false
    toks
    (let [stack []          ; open blocks: {:kind :turns :name}
          defined {}        ; helpers whose definition has begun
          closed {}         ; helpers whose definition has ended
          max-turns translate.limits.cost]
      (var ok? true)
      (var i 1)
      (fn at [k] (or (. toks (+ i k)) ""))
      (fn work []
        (accumulate [w 1 _ b (ipairs stack)] (* w (or b.turns 1))))
      (while (and ok? (<= i (length toks)))
        (let [t (. toks i)]
          (if (= t "math")
              (do (set ok? (and (= (at 1) ".") (. lua-math (at 2)) (= (at 3) "(") true))
                  (set i (+ i 3)))
              (= t ".") (set ok? false)
              (= t "function")
              (do (table.insert stack {:kind :function :name (when (= (. toks (- i 1)) "local") (at 1))})
                  (set i (+ i 1)))
              (= t "if") (do (table.insert stack {:kind :if}) (set i (+ i 1)))
              (= t "for")
              ;; for vN = A, B[, C] do: whole numbers, maybe negative ("-" then digits).
              (let [(a after-a) (signed toks (+ i 3))
                    (b after-b) (signed toks (+ after-a 1))
                    three? (= (. toks after-b) ",")
                    (c after-c) (if three? (signed toks (+ after-b 1)) (values 1 after-b))
                    turns (and (: (at 1) :match "^v%d+$") (= (at 2) "=") (= (. toks after-a) ",")
                               (loop-turns a b c))]
                (if (and turns (<= turns translate.limits.loop-turns) (= (. toks after-c) "do"))
                    (do (table.insert stack {:kind :for : turns})
                        (set ok? (<= (work) max-turns))
                        (set i (+ after-c 1)))
                    (set ok? false)))
              (= t "end")
              (let [b (table.remove stack)]
                (when (and b b.name) (tset closed b.name true))
                (set ok? (not= nil b))
                (set i (+ i 1)))
              (= t "do") (set ok? false)
              (t:match "^v%d+$")
              ;; A variable holds a number: never called.
              (do (set ok? (not= (at 1) "("))
                  (set i (+ i 1)))
              (or (. lua-words t) (number? t) (not (t:match "^[%a_]")))
              (set i (+ i 1))
              (t:match "^sdCustom%d*Fn%d+$")
              ;; A helper's name: its one definition, or a call of one defined before.
              (do (set ok? (if (= (. toks (- i 1)) "function")
                               (when (not (. defined t)) (tset defined t true) true)
                               (and (. closed t) (= (at 1) "(") true)))
                  (set i (+ i 1)))
              (set ok? false))))
      (and ok? (= 0 (length stack))))))

(fn check-glsl [text name]
  "True when `text` is GLSL of the translator's kind for the function `name`."
  (case (tokens text)
    nil false
    toks
    (let [braces []]
      (var ok? true)
      (var pending nil)   ; a for header's turns, until its {
      (var i 1)
      (fn at [k] (or (. toks (+ i k)) ""))
      (while (and ok? (<= i (length toks)))
        (let [t (. toks i)]
          (if (= t "for")
              ;; for ( int iN = A ; iN <= B ; iN ++ | iN += C ) {
              (let [(a after-a) (signed toks (+ i 5))
                    cmp (. toks (+ after-a 2))
                    (b after-b) (signed toks (+ after-a 3))
                    update (. toks (+ after-b 2))
                    (c) (if (= update "++") (values 1) (signed toks (+ after-b 3)))
                    turns (and (= (at 1) "(") (= (at 2) "int") (: (at 3) :match "^i%d+$")
                               (= (at 4) "=") (= (. toks after-a) ";")
                               (or (= cmp "<=") (= cmp ">=")) (= (. toks after-b) ";")
                               (or (= update "++") (= update "+="))
                               (loop-turns a b c))]
                (set ok? (and turns (<= turns translate.limits.loop-turns) true))
                (set pending turns)
                (set i (+ i 2)))
              (= t "{") (do (table.insert braces (or pending 1)) (set pending nil) (set i (+ i 1))
                            (set ok? (<= (accumulate [w 1 _ b (ipairs braces)] (* w b))
                                         translate.limits.cost)))
              (= t "}") (do (set ok? (not= nil (table.remove braces))) (set i (+ i 1)))
              (= t ".") (do (set ok? (and (. swizzles (at 1))
                                           (or (= (. toks (- i 1)) "p") (: (. toks (- i 1)) :match "^[va]%d+$"))
                                           true))
                            (set i (+ i 2)))
              (or (. glsl-words t) (number? t) (t:match "^[via]%d+$") (= t name)
                  (and (= (t:sub 1 (length name)) name) (: (t:sub (+ 1 (length name))) :match "^Fn%d+$"))
                  (not (t:match "^[%a_]")))
              (set i (+ i 1))
              (set ok? false))))
      (and ok? (= 0 (length braces))))))

(fn check-data [c]
  "Nil when the custom node data `c` (from the worker) is as the translator writes it,
else why not."
  (if (not (and (= (type c) :table) (= (type c.glsl) :string) (= (type c.lua) :string)
                (= (type c.glsl-name) :string) (c.glsl-name:match "^sdCustom%d+$")
                (= (type c.key) :string) (= (type c.params) :table)))
      "its data is not a translation"
      (not (check-glsl c.glsl c.glsl-name)) "its GLSL is not the translator's"
      (not (check-lua c.lua)) "its Lua is not the translator's"
      (not= c.key (digest c.glsl)) "its digest does not match its GLSL"))

;;; The lowering's side: a descriptor from the data

(local cache {})
(var cached 0)

(fn estimate-factor [node]
  ;; The factor of node's distance read as an estimate (see descriptor), when below
  ;; the one its steps take: the measure's (`factor` of it), nil otherwise.
  (let [measured (?. node :custom :measured)
        k (or node.lipschitz 1)]
    (when (and (= (type measured) :number) (finite-number? measured) (>= measured 0))
      (let [e (factor measured)]
        (when (< e k) e)))))

(fn estimate! [desc node]
  ;; `desc` (a copy of the cached descriptor) with the estimate's scale after its
  ;; own, when the node has one (estimate-factor); its kind says so, as the key must.
  (case (estimate-factor node)
    e (let [pack desc.pack]
        (set desc.kind (.. desc.kind ":estimate"))
        (set desc.args (doto (icollect [_ a (ipairs desc.args)] a)
                         (table.insert {:name :estimate :type :float :estimate? true})))
        (set desc.arg-size (+ desc.arg-size 1))
        (set desc.pack (fn [o] (doto (pack o) (table.insert (/ 1 e))))))))

(fn descriptor [node]
  "The primitive-like descriptor (see src/sdf/primitives.fnl) of custom node `node`
(validated data: :custom {:glsl :lua :glsl-name :key :params}, :params, :bounds,
:lipschitz), or nil for any other node. Its function takes the parameters in the
order of the fn's arguments, then 1 / :lipschitz, by which it multiplies. The
descriptors of nodes with the same texts share their GLSL and their Lua function."
  (when (= node.kind :custom)
    (let [c node.custom
          ;; The texts themselves key the cache: checked once, then found again at
          ;; every lowering (each value edit lowers the scene again).
          ;; The parameters' names too: two functions that differ only in them have
          ;; the same texts, and each packs its own :params.
          text-key (and (= (type c) :table) (= (type c.glsl) :string) (= (type c.lua) :string)
                        (= (type c.glsl-name) :string) (= (type c.key) :string)
                        (= (type c.params) :table)
                        (accumulate [ok? true _ n (ipairs c.params)] (and ok? (= (type n) :string)))
                        (.. c.glsl-name "\n" c.key "\n" c.glsl "\n" c.lua "\n" (table.concat c.params " ")))
          bad (if (not text-key) "its data is not a translation"
                  (not (. cache text-key)) (check-data c))
          _ (when bad
              (let [reason (.. "a custom node: " bad " (refused)")]
                (error {:lower-error (.. (tostring node.path) ": " reason) : reason : node})))
          key text-key]
      (when (not (. cache key))
        (when (> cached 256)
          (each [k (each-pair cache)] (tset cache k nil))
          (set cached 0))
        (set cached (+ cached 1))
        (let [names c.params
              args (icollect [i _ (ipairs names)] {:name (.. "a" i) :type :float})]
          (table.insert args {:name :scale :type :float})
          (tset cache key
                {:kind (.. "custom:" c.glsl-name ":" c.key)
                 :doc "A distance function written in the scene."
                 :params []
                 :class :bound
                 :lipschitz 1
                 : args
                 :arg-size (length args)
                 :pack (fn [o]
                         (let [out (icollect [_ n (ipairs names)] (. o.params n))]
                           (table.insert out (/ 1 o.lipschitz))
                           out))
                 :glsl-name c.glsl-name
                 :glsl c.glsl
                 :cpu (translate.compile-lua c.lua)
                 :bounds (fn [o] o.bounds)})))
      ;; The node's own factor, for --tree: the function divides by it already, and
      ;; nothing reads a primitive's factor to divide again. A node declared steeper
      ;; than it measured takes the measure's factor where the field is read as an
      ;; estimate of the distance (a soft shadow's penumbra, occlusion: the declared
      ;; factor would darken them as if the surface were that much nearer) and the
      ;; declared one where a ray steps: its scale is followed by an :estimate? one.
      (doto (collect [k v (each-pair (. cache key))] k v)
        (estimate! node)
        (tset :lipschitz (or node.lipschitz 1))
        ;; A declared factor taken on trust (:trust-lipschitz), said as such with
        ;; what the loader measured.
        (tset :lipschitz-note
              (if (and node.trust-lipschitz node.lipschitz)
                  (string.format "declared and trusted: :trust-lipschitz, measured %.3g%s"
                                 (or (?. c :measured) 0)
                                 (if (> (or (?. c :measured) 0) (* node.lipschitz limits.declared-slack))
                                     ", steps may pass the surface" ""))
                  (case (estimate-factor node)
                    e (string.format "declared, steps divided by it; measured %.3g, so soft shadows and occlusion read it divided by %.3g"
                                     c.measured e))))))))

{: capture : check-data : measure : check-bounds : factor : digest : descriptor : find-form : check-lua : check-glsl
 : range-samples : sample-cost : limits}

;; The operation catalogue: transforms, combinations and domain operations, one
;; descriptor each, in the same spirit as the primitives (src/sdf/primitives.fnl).
;; Every descriptor has :kind :doc :params :role, its GLSL text and name, its CPU form,
;; and says how it changes the exactness, the Lipschitz factor and the bounds of its
;; children. Roles:
;;   :point    one child; maps the point before the child:  vec3 opX(vec3 p, args)
;;             / (fn [x y z ...]) -> x y z; optional :post distance step after it
;;   :distance one child; changes its distance:  float opX(float d, vec3 p, args)
;;             / (fn [d x y z ...]) -> d
;;   :combine  two or more children, folded left:  float opX(float a, float b, args)
;;             / (fn [a b ...]) -> d; and a material weight of the first operand,
;;             float wX(float a, float b, args) / :cpu-weight (fn [a b ...]) -> w
;;   :cells    one child evaluated in several cells (repetition), the nearest kept:
;;             vec3 opX(vec3 p, args, int cell) / (fn [cell x y z ...]) -> x y z
;; :class-doc says it in words for `--kinds`.
;; :class-of (fn [o children]) -> :exact or :bound, where children are the lowered
;; children's infos ({:class :bounds}); :lipschitz-of (fn [o children]) -> k >= 1 (the
;; lowering divides the distance by k, unless the :post step corrects it point by
;; point: :corrects? true, as twist and bend do); optional :box-of (fn [o child-boxes]) ->
;; {:lo :hi}, a box tighter than the symmetric bounds (see box-of in src/sdf/lower.fnl);
;; :bounds-of (fn [o children]) -> half extents
;; or nil (unbounded).
;; A :cells node may say how few cells need the child itself (see src/sdf/lower.fnl):
;; :own-cell? (fn [o child]) true when the point's own cell always holds the nearest
;; copy; :boxed-neighbours? (fn [o child]) true when a copy's box, in the neighbour
;; cells, is a bound good enough to take the copy's place there. `child`: the
;; lowered child's info ({:even :box :children}).
;; :keeps-even: true, or (fn [o axis]) -> boolean, when the node's distance is even
;; and never decreasing along that axis wherever its children's are (see a
;; primitive's :even in src/sdf/primitives.fnl): min and max of such functions, and
;; moves that leave that coordinate alone, are too.
;; :keeps-symmetric: true, or (fn [o axis]) -> boolean, when the node's distance and
;; material are the same at -v as at v along that axis (about its origin) wherever
;; its children's are: :symmetric in a lowered node's info (a primitive's :symmetric
;; or :even). Functions of the children's distances (unions, subtractions, smooth
;; blends, round, onion) and point maps that commute with the reflection keep it; a
;; :keeps-even node keeps it too. :symmetric-of (fn [o children axis]) -> boolean
;; instead, for a node symmetric whatever its children (a mirror across that axis).

(local {: sqrt : abs : min : max : floor : sin : cos : log : exp : atan2 : pi} math)

(fn round [v] (floor (+ v 0.5)))

(fn rad [deg] (* deg (/ pi 180)))

(fn all-exact [_ children]
  (var exact? true)
  (each [_ c (ipairs children)] (when (not= c.class :exact) (set exact? false)))
  (if exact? :exact :bound))

(fn first-class [_ children] (. children 1 :class))
(fn bound-class [] :bound)
(fn first-bounds [_ children] (. children 1 :bounds))

(fn merge-bounds [_ children]
  (var out [0 0 0])
  (each [_ c (ipairs children) &until (= out nil)]
    (if c.bounds
        (let [[x y z] c.bounds [ox oy oz] out]
          (set out [(max x ox) (max y oy) (max z oz)]))
        (set out nil)))
  out)

(fn grow-bounds [b by]
  (when b (let [[x y z] b] [(+ x by) (+ y by) (+ z by)])))

(fn rotation-rows [o]
  "Rows of the matrix that maps a world point into the child's frame (the inverse,
i.e. the transpose, of the rotation): [r1x r1y r1z r2x ... r3z]."
  (let [m (if o.axis
              ;; Rodrigues' formula for a rotation by :angle about the unit :axis.
              (let [[x y z] o.axis
                    a (rad o.angle) c (cos a) s (sin a) t (- 1 c)]
                [[(+ (* t x x) c) (- (* t x y) (* s z)) (+ (* t x z) (* s y))]
                 [(+ (* t x y) (* s z)) (+ (* t y y) c) (- (* t y z) (* s x))]
                 [(- (* t x z) (* s y)) (+ (* t y z) (* s x)) (+ (* t z z) c)]])
              ;; Degrees about x, then y, then z: R = Rz Ry Rx.
              (let [[ax ay az] o.angles
                    cx (cos (rad ax)) sx (sin (rad ax))
                    cy (cos (rad ay)) sy (sin (rad ay))
                    cz (cos (rad az)) sz (sin (rad az))]
                [[(* cz cy) (- (* cz sy sx) (* sz cx)) (+ (* cz sy cx) (* sz sx))]
                 [(* sz cy) (+ (* sz sy sx) (* cz cx)) (- (* sz sy cx) (* cz sx))]
                 [(- sy) (* cy sx) (* cy cx)]]))
        [[a b c] [d e f] [g h i]] m]
    ;; Transpose: the child sees R^T p.
    [a d g b e h c f i]))

(fn rotate-bounds [o children]
  (let [b (. children 1 :bounds)]
    (when b
      (let [[hx hy hz] b
            [a b2 c d e f g h i] (rotation-rows o)]
        ;; The box of the rotated box: |R| h, with R = the transpose of the rows.
        [(+ (* (abs a) hx) (* (abs d) hy) (* (abs g) hz))
         (+ (* (abs b2) hx) (* (abs e) hy) (* (abs h) hz))
         (+ (* (abs c) hx) (* (abs f) hy) (* (abs i) hz))]))))

(fn shear-factor [k rho]
  ;; Largest singular value of I + v e^T with |v| = k rho (v orthogonal to e): the
  ;; Lipschitz factor of twisting or bending a point at distance rho from the axis.
  (let [v (* (abs k) rho)]
    (* 0.5 (+ v (sqrt (+ (* v v) 4))))))

(fn cell-count-of [o]
  (accumulate [n 1 _ v (ipairs o.period)] (if (> v 0) (* n 2) n)))

(fn fits-cell? [o children]
  ;; A child that stays inside its cell (half a period on each repeated axis) is
  ;; found exactly by looking at its own cell and the nearest neighbour.
  (let [b (. children 1 :bounds)]
    (and b (accumulate [ok? true i v (ipairs o.period)]
             (and ok? (or (= v 0) (<= (. b i) (* 0.5 v))))))))

(fn repeat-own-cell? [o child]
  ;; A child even and never decreasing along every repeated axis, about the cell's
  ;; centre: the copy in the point's own cell (the rounded one, clamped when
  ;; limited) is nearest, as |v - id period| is least there on each axis.
  (accumulate [ok? (not= nil child.even) i v (ipairs o.period)]
    (and ok? (or (= v 0) (. child.even i)))))

;; The share of a period a copy's box must leave free on each side of its cell for
;; the neighbours to be drawn by their boxes: the bound there is then at least this
;; much of a period (fewer, longer steps between the copies).
(local neighbour-margin 0.1)

(fn repeat-boxed-neighbours? [o child]
  ;; A child that is a tree (a box costs less than it) whose box stays inside its
  ;; cell with a margin: from any point of its own cell, a neighbour's box is at
  ;; least that margin away, so its distance there is a bound for the neighbour
  ;; that never makes a hit of it.
  (let [box child.box]
    (and box (> (length child.children) 0)
         (accumulate [ok? true i v (ipairs o.period)]
           (and ok? (or (= v 0)
                        (<= (math.max (- (. box.lo i)) (. box.hi i))
                            (* v (- 0.5 neighbour-margin)))))))))

(fn repeat-bounds [o children]
  (let [b (. children 1 :bounds)]
    (when (and b (not o.count))
      (var unbounded? false)
      (each [_ v (ipairs o.period)] (when (> v 0) (set unbounded? true)))
      (when (not unbounded?) b))
    (when (and b o.count)
      (icollect [i v (ipairs o.period)] (+ (. b i) (* v (. o.count i)))))))

;; The GLSL and CPU forms of the repetition cells share this rule: on each repeated
;; axis, the cell of the point and its nearer neighbour; the bits of `cell` choose,
;; axis by axis in x y z order, the neighbour (1) or the own cell (0).
(fn repeat-cell [cell x y z px py pz lx ly lz]
  (var bit 1)
  (fn axis [v period limit]
    (if (= period 0) v
        (let [id (round (/ v period))
              side (if (>= (- v (* id period)) 0) 1 -1)
              pick (% (floor (/ cell bit)) 2)
              id (+ id (* pick side))
              id (if (< limit 0) id (max (- limit) (min limit id)))]
          (set bit (* bit 2))
          (- v (* id period)))))
  (let [rx (axis x px lx) ry (axis y py ly) rz (axis z pz lz)]
    (values rx ry rz)))

(local repeat-glsl "vec3 opRepeat(vec3 p, vec3 period, vec3 limit, int cell) {
    vec3 q = p;
    int bit = 1;
    for (int a = 0; a < 3; a++) {
        if (period[a] > 0.0) {
            float id = floor(p[a] / period[a] + 0.5);
            float side = p[a] - id * period[a] >= 0.0 ? 1.0 : -1.0;
            id += float((cell / bit) % 2) * side;
            if (limit[a] >= 0.0) {
                id = clamp(id, -limit[a], limit[a]);
            }
            q[a] = p[a] - id * period[a];
            bit *= 2;
        }
    }
    return q;
}")

;; The repetition's GLSL for the axes it repeats along (a variant per set of axes):
;; the same arithmetic as repeat-glsl, axis by axis, without its loop over the three
;; axes and its branches on the period and the limit, which llvmpipe runs for every
;; axis, masked (colonnade: 18% of a frame).
(fn repeat-variant [axes]
  (let [name (.. "opRepeat" (table.concat (icollect [_ a (ipairs axes)] (a:upper))))
        lines [(.. "vec3 " name "(vec3 p, vec3 period, vec3 limit, int cell) {")
               "    vec3 q = p;"]]
    (each [k a (ipairs axes)]
      (let [id (.. "id" (a:upper))
            bit (. [1 2 4] k)]
        (table.insert lines (.. "    float " id " = floor(p." a " / period." a " + 0.5);"))
        (table.insert lines (.. "    " id " += float((cell / " bit ") % 2) * (p." a " - " id
                                " * period." a " >= 0.0 ? 1.0 : -1.0);"))
        (table.insert lines (.. "    " id " = limit." a " >= 0.0 ? clamp(" id ", -limit." a
                                ", limit." a ") : " id ";"))
        (table.insert lines (.. "    q." a " = p." a " - " id " * period." a ";"))))
    (table.insert lines "    return q;")
    (table.insert lines "}")
    {:glsl-name name :glsl (table.concat lines "\n") :cpu repeat-cell}))

(local repeat-variants
  (collect [_ axes (ipairs [["x"] ["y"] ["z"] ["x" "y"] ["x" "z"] ["y" "z"] ["x" "y" "z"]])]
    (table.concat axes) (repeat-variant axes)))

(fn repeat-axes [o]
  ;; "x", "xz", ...: the axes `o` repeats along.
  (table.concat (icollect [i v (ipairs o.period)] (when (> v 0) (. ["x" "y" "z"] i)))))

(fn polar-cell [cell x y z sector]
  ;; The point in the frame of the sector it lies in (cell 0) or of the neighbour
  ;; sector on its side (cell 1).
  (let [a (atan2 y x)
        id (round (/ a sector))
        side (if (>= (- a (* id sector)) 0) 1 -1)
        id (+ id (* cell side))
        b (- a (* id sector))
        r (sqrt (+ (* x x) (* y y)))]
    (values (* r (cos b)) (* r (sin b)) z)))

;; Taylor coefficients of sin (odd powers to 11) and cos (even powers to 12): within
;; 60 degrees the first term left out is under 3e-10.
(local polar-narrow
  {:glsl-name "opPolarNarrow"
   :glsl "vec3 opPolarNarrow(vec3 p, float sector, vec2 turn, int cell) {
    float a = atan(p.y, p.x);
    float id = floor(a / sector + 0.5);
    float b = a - id * sector;
    float side = b >= 0.0 ? 1.0 : -1.0;
    float r = length(p.xy);
    float b2 = b * b;
    float s = b * (1.0 + b2 * (-0.16666666666666666 + b2 * (0.008333333333333333 + b2 * (-0.0001984126984126984 + b2 * (2.7557319223985893e-06 + b2 * -2.505210838544172e-08)))));
    float c = 1.0 + b2 * (-0.5 + b2 * (0.041666666666666664 + b2 * (-0.001388888888888889 + b2 * (2.48015873015873e-05 + b2 * (-2.755731922398589e-07 + b2 * 2.08767569878681e-09)))));
    vec2 q = r * vec2(c, s);
    float k = float(cell);
    float tc = mix(1.0, turn.x, k);
    float ts = turn.y * side * k;
    return vec3(tc * q.x + ts * q.y, tc * q.y - ts * q.x, p.z);
}"
   :cpu polar-cell})

(fn fold-schedule [n]
  ;; How a polar repetition of `n` sectors folds a point into the half sector
  ;; [0, pi / n] by reflections: across y = 0 (always), x = 0 (n even) and y = x (n a
  ;; multiple of 4), each exact in float, then across the lines at the angles listed,
  ;; each halving (rounded up) the number of half sectors the point may lie in. Every
  ;; line is at a multiple of pi / n: a mirror line of the copies when the child is
  ;; symmetric in y.
  (let [pre (if (= 0 (% n 4)) 4 (= 0 (% n 2)) 2 1)
        angles []]
    (var left (/ n pre))
    (while (> left 1)
      (let [c (math.ceil (/ left 2))]
        (table.insert angles (* c (/ pi n)))
        (set left c)))
    {: pre : angles}))

(local polar-folds {})

(fn polar-fold [n]
  ;; The polar form for a child symmetric in y (see :variant-of below): the point
  ;; folded into its half sector, by fold-schedule's reflections, is the child's point
  ;; in its own sector or its mirror image there, where the child's value is the same
  ;; (no atan, no sine or cosine: colonnade's 12 flutes, a quarter of a frame). The
  ;; neighbour sector's point is the folded one turned by the sector. The CPU form is
  ;; the atan one, the definition the GPU is checked against. Each fold line's normal
  ;; (sin a, -cos a), pointing to the kept side, two to a row.
  (let [{: pre : angles} (fold-schedule n)
        k (length angles)
        rows (math.ceil (/ k 2))
        name (.. "opPolarFold" pre "x" k)]
    (when (not (. polar-folds name))
      (let [lines [(.. "vec3 " name "(vec3 p, float sector, vec2 turn, "
                       (table.concat (fcollect [i 1 rows] (.. "vec4 fold" i ", ")))
                       "int cell) {")
                   (if (= pre 1) "    vec2 q = vec2(p.x, abs(p.y));" "    vec2 q = abs(p.xy);")]]
        (when (= pre 4) (table.insert lines "    q = vec2(max(q.x, q.y), min(q.x, q.y));"))
        (for [i 1 k]
          (let [n (.. "fold" (math.ceil (/ i 2)) (if (= 1 (% i 2)) ".xy" ".zw"))]
            (table.insert lines (.. "    q -= 2.0 * min(dot(q, " n "), 0.0) * " n ";"))))
        (each [_ l (ipairs ["    float k = float(cell);"
                            "    float tc = mix(1.0, turn.x, k);"
                            "    float ts = turn.y * k;"
                            "    return vec3(tc * q.x + ts * q.y, tc * q.y - ts * q.x, p.z);"
                            "}"])]
          (table.insert lines l))
        (tset polar-folds name
              {:glsl-name name :glsl (table.concat lines "\n") :cpu polar-cell
               :args (let [args [{:name :sector :type :float} {:name :turn :type :vec2}]]
                       (for [i 1 rows] (table.insert args {:name (.. "fold" i) :type :vec4}))
                       args)
               :pack (fn [o]
                       (let [s (/ (* 2 pi) o.count)
                             out [s (cos s) (sin s)]]
                         (each [_ a (ipairs (. (fold-schedule o.count) :angles))]
                           (table.insert out (sin a))
                           (table.insert out (- (cos a))))
                         (when (= 1 (% k 2)) (table.insert out 0) (table.insert out 0))
                         out))})))
    (. polar-folds name)))

(fn symmetric-rotation? [o axis]
  ;; A rotation that maps the axis onto itself commutes with the reflection along it.
  (let [rows (rotation-rows o)]
    (accumulate [ok? true _ i (ipairs [1 2 3])]
      (and ok? (or (= i axis)
                   (and (= 0 (. rows (+ (* 3 (- i 1)) axis)))
                        (= 0 (. rows (+ (* 3 (- axis 1)) i)))))))))

(fn axis-permutation [o]
  ;; "ZYX" and the like when the rotation only permutes the axes (with signs): each
  ;; row of the child's matrix has one entry of magnitude 1 (within 1e-12; cos 90
  ;; degrees is 6e-17 in double) and the rest 0. The letter is the column of row i's
  ;; entry: the coordinate the child's i-th one is taken from.
  (let [rows (rotation-rows o)
        letters []]
    (for [i 1 3]
      (var found nil)
      (var ok? true)
      (for [j 1 3]
        (let [v (abs (. rows (+ (* 3 (- i 1)) j)))]
          (if (< (abs (- v 1)) 1e-12) (if found (set ok? false) (set found j))
              (>= v 1e-12) (set ok? false))))
      (table.insert letters (when (and ok? found) (. ["X" "Y" "Z"] found))))
    (when (= 3 (length letters)) (table.concat letters))))

(local rotate-permutations {})

(fn rotate-permutation [perm]
  ;; The rotation by swizzles: each coordinate of the child's point is one of the
  ;; point's times its row's entry there (+-1; the 6e-17 beside it left out: under
  ;; float32's rounding of the product). 3 multiplications instead of 3 dot products
  ;; (colonnade's arches, a quarter turn about y: 3% of a frame). The CPU form keeps
  ;; the whole matrix.
  (when (not (. rotate-permutations perm))
    (let [name (.. "opRotate" perm)
          terms (fcollect [i 1 3]
                  (let [c (: (perm:sub i i) :lower)]
                    (.. "r" (- i 1) "." c " * p." c)))]
      (tset rotate-permutations perm
            {:glsl-name name
             :glsl (.. "vec3 " name "(vec3 p, vec3 r0, vec3 r1, vec3 r2) {\n"
                       "    return vec3(" (table.concat terms ", ") ");\n}")
             :cpu (fn [x y z a b c d e f g h i]
                    (values (+ (* a x) (* b y) (* c z)) (+ (* d x) (* e y) (* f z))
                            (+ (* g x) (* h y) (* i z))))})))
  (. rotate-permutations perm))

(fn mirror-cpu [x y z nx ny nz]
  (let [k (* 2 (min (+ (* x nx) (* y ny) (* z nz)) 0))]
    (values (- x (* k nx)) (- y (* k ny)) (- z (* k nz)))))

;; A mirror across a plane of the axes (a normal of +-1 along one axis, 0 on the
;; others): the coordinate along it made +-|v|, the same floats as the general form's
;; p - 2 min(p.n, 0) n, in 1 operation instead of 7 (colonnade's two rows of
;; columns: 4% of a frame).
(local mirror-axes
  (collect [i axis (ipairs ["x" "y" "z"])]
    i (let [name (.. "opMirror" (axis:upper))
            parts (icollect [_ a (ipairs ["x" "y" "z"])]
                    (if (= a axis) (.. "n." a " * abs(p." a ")") (.. "p." a)))]
        {:glsl-name name
         :glsl (.. "vec3 " name "(vec3 p, vec3 n) {\n    return vec3("
                   (table.concat parts ", ") ");\n}")
         :cpu mirror-cpu})))

(fn mirror-axis [o]
  ;; 1, 2 or 3 when the normal is +-1 along that axis and 0 along the others.
  (accumulate [found nil i v (ipairs o.normal)]
    (if (= 1 (abs v)) (when (= 2 (accumulate [zeros 0 _ w (ipairs o.normal)]
                                   (if (= 0 w) (+ zeros 1) zeros)))
                        i)
        found)))

(local operations
  [;;; Transforms
   {:kind :translate :role :point
    :class-doc "keeps"
    :doc "Moves its child by :offset."
    :params [{:name :offset :type :vec3 :default [0 0 0]}]
    :children [1 1]
    :args [{:name :t :type :vec3}] :pack (fn [o] o.offset)
    :glsl-name "opTranslate"
    :glsl "vec3 opTranslate(vec3 p, vec3 t) {
    return p - t;
}"
    :cpu (fn [x y z tx ty tz] (values (- x tx) (- y ty) (- z tz)))
    :keeps-even (fn [o axis] (= 0 (. o.offset axis)))
    :class-of first-class
    :bounds-of (fn [o children]
                 (let [b (. children 1 :bounds)]
                   (when b (icollect [i v (ipairs b)] (+ v (abs (. o.offset i)))))))
    ;; The symmetric bounds above hold the moved child about the old origin; its box
    ;; ({:lo :hi}, see src/sdf/lower.fnl) moves with it.
    :box-of (fn [o [child]]
              {:lo (icollect [i v (ipairs child.lo)] (+ v (. o.offset i)))
               :hi (icollect [i v (ipairs child.hi)] (+ v (. o.offset i)))})}
   {:kind :rotate :role :point
    :class-doc "keeps"
    :doc "Rotates its child: :angles [x y z] in degrees (about x, then y, then z), or :axis and :angle."
    :params [{:name :angles :type :vec3 :default [0 0 0]}
             {:name :axis :type :direction :optional? true}
             {:name :angle :type :degrees :min -3600 :max 3600 :default 0}]
    :children [1 1]
    :args [{:name :r0 :type :vec3} {:name :r1 :type :vec3} {:name :r2 :type :vec3}]
    :pack rotation-rows
    :glsl-name "opRotate"
    :glsl "vec3 opRotate(vec3 p, vec3 r0, vec3 r1, vec3 r2) {
    return vec3(dot(r0, p), dot(r1, p), dot(r2, p));
}"
    :cpu (fn [x y z a b c d e f g h i]
           (values (+ (* a x) (* b y) (* c z)) (+ (* d x) (* e y) (* f z))
                   (+ (* g x) (* h y) (* i z))))
    :variant-of (fn [o] (let [perm (axis-permutation o)] (when perm (rotate-permutation perm))))
    :keeps-symmetric symmetric-rotation?
    :class-of first-class
    :bounds-of rotate-bounds}
   {:kind :scale :role :point
    :class-doc "keeps"
    :doc "Scales its child uniformly by :factor (the distance is scaled back: stays exact)."
    :params [{:name :factor :type :positive :default 1}]
    :children [1 1]
    :args [{:name :s :type :float}] :pack (fn [o] [o.factor])
    :glsl-name "opScale"
    :glsl "vec3 opScale(vec3 p, float s) {
    return p / s;
}"
    :cpu (fn [x y z s] (values (/ x s) (/ y s) (/ z s)))
    :keeps-symmetric true
    :post {:glsl-name "opScaleDistance"
           :glsl "float opScaleDistance(float d, vec3 p, float s) {
    return d * s;
}"
           :cpu (fn [d _ _ _ s] (* d s))}
    :class-of first-class
    :bounds-of (fn [o children]
                 (let [b (. children 1 :bounds)]
                   (when b (icollect [_ v (ipairs b)] (* v o.factor)))))}
   {:kind :stretch :role :point
    :class-doc "bound"
    :doc "Scales its child by :factors [x y z], not uniformly (a bound)."
    :params [{:name :factors :type :size3 :default [1 1 1]}]
    :children [1 1]
    :args [{:name :s :type :vec3} {:name :m :type :float}]
    :pack (fn [o] (let [[x y z] o.factors] [x y z (min x y z)]))
    :glsl-name "opStretch"
    :glsl "vec3 opStretch(vec3 p, vec3 s, float m) {
    return p / s;
}"
    :cpu (fn [x y z sx sy sz] (values (/ x sx) (/ y sy) (/ z sz)))
    :keeps-symmetric true
    ;; d(p / s) changes at most 1 / min(s) per unit: times min(s) it is a bound.
    :post {:glsl-name "opStretchDistance"
           :glsl "float opStretchDistance(float d, vec3 p, vec3 s, float m) {
    return d * m;
}"
           :cpu (fn [d _ _ _ _ _ _ m] (* d m))}
    :class-of bound-class
    :bounds-of (fn [o children]
                 (let [b (. children 1 :bounds)]
                   (when b (icollect [i v (ipairs b)] (* v (. o.factors i))))))}

   ;;; Domain operations
   {:kind :mirror :role :point
    :class-doc "bound (exact when the child is on the normal's side)"
    :doc "Mirrors its child across the plane through the origin with :normal (the child's half on the normal's side is kept)."
    :params [{:name :normal :type :direction :default [1 0 0]}]
    :children [1 1]
    :args [{:name :n :type :vec3}] :pack (fn [o] o.normal)
    :glsl-name "opMirror"
    :glsl "vec3 opMirror(vec3 p, vec3 n) {
    return p - 2.0 * min(dot(p, n), 0.0) * n;
}"
    :cpu mirror-cpu
    :variant-of (fn [o] (. mirror-axes (mirror-axis o)))
    ;; A normal across the axis leaves that coordinate alone.
    :keeps-even (fn [o axis] (= 0 (. o.normal axis)))
    ;; Mirrored across that axis itself, symmetric whatever the child.
    :symmetric-of (fn [o children axis]
                    (or (= 1 (abs (. o.normal axis)))
                        (and (= 0 (. o.normal axis)) (= true (?. children 1 :symmetric axis)))))
    ;; The box of the child's box and its mirror image: holds the kept half and its
    ;; image (tighter than the bounds' circle about the normal).
    :box-of (fn [o [child]]
              (let [[nx ny nz] o.normal
                    lo [math.huge math.huge math.huge]
                    hi [(- math.huge) (- math.huge) (- math.huge)]]
                (each [_ x (ipairs [(. child.lo 1) (. child.hi 1)])]
                  (each [_ y (ipairs [(. child.lo 2) (. child.hi 2)])]
                    (each [_ z (ipairs [(. child.lo 3) (. child.hi 3)])]
                      (let [k (* 2 (+ (* x nx) (* y ny) (* z nz)))]
                        (each [_ q (ipairs [[x y z] [(- x (* k nx)) (- y (* k ny)) (- z (* k nz))]])]
                          (for [i 1 3]
                            (tset lo i (min (. lo i) (. q i)))
                            (tset hi i (max (. hi i) (. q i)))))))))
                {: lo : hi}))
    ;; Exact when the child lies on the normal's side; otherwise still a bound.
    :class-of bound-class
    :bounds-of (fn [o children]
                 (let [b (. children 1 :bounds)]
                   (when b (let [r (sqrt (+ (* (. b 1) (. b 1)) (* (. b 2) (. b 2))
                                            (* (. b 3) (. b 3))))]
                             [r r r]))))}
   {:kind :elongate :role :point
    :class-doc "keeps"
    :doc "Stretches its child by inserting :size (full extents) of straight extrusion at its centre."
    :params [{:name :size :type :lengths3 :default [1 0 0]}]
    :children [1 1]
    :args [{:name :h :type :vec3}]
    :pack (fn [o] (icollect [_ v (ipairs o.size)] (* 0.5 v)))
    :glsl-name "opElongate"
    :glsl "vec3 opElongate(vec3 p, vec3 h) {
    return p - clamp(p, -h, h);
}"
    :cpu (fn [x y z hx hy hz]
           (values (- x (max (- hx) (min hx x))) (- y (max (- hy) (min hy y)))
                   (- z (max (- hz) (min hz z)))))
    :keeps-symmetric true
    ;; Exact outside; inside the inserted part the distance is 0 or the child's.
    :class-of first-class
    :bounds-of (fn [o children]
                 (let [b (. children 1 :bounds)]
                   (when b (icollect [i v (ipairs b)] (+ v (* 0.5 (. o.size i)))))))}
   {:kind :twist :role :point
    :class-doc "bound, Lipschitz from the child's radius"
    :doc "Twists its child about the z axis by :angle degrees per unit of height (Lipschitz factor grows with the child's radius)."
    :params [{:name :angle :type :degrees :min -3600 :max 3600 :default 45}]
    :children [1 1]
    ;; k in radians per unit, and rho0 the child's radius about z (from its bounds).
    :args [{:name :k :type :float} {:name :rho0 :type :float}]
    :pack (fn [o child] (let [[hx hy] child.bounds] [(rad o.angle) (sqrt (+ (* hx hx) (* hy hy)))]))
    :glsl-name "opTwist"
    :glsl "vec3 opTwist(vec3 p, float k, float rho0) {
    float c = cos(k * p.z);
    float s = sin(k * p.z);
    return vec3(c * p.x + s * p.y, -s * p.x + c * p.y, p.z);
}"
    :cpu (fn [x y z k]
           (let [c (cos (* k z)) s (sin (* k z))]
             (values (+ (* c x) (* s y)) (- (* c y) (* s x)) z)))
    ;; The twist stretches space by at most the shear factor at the largest radius a
    ;; straight path from p to the child passes: max(radius of p, rho0). Dividing by
    ;; it at each point keeps the distance a bound everywhere, near or far.
    :post {:glsl-name "opTwistDistance"
           :glsl "float opTwistDistance(float d, vec3 p, float k, float rho0) {
    float v = abs(k) * max(length(p.xy), rho0);
    return d / (0.5 * (v + sqrt(v * v + 4.0)));
}"
           :cpu (fn [d x y _ k rho0]
                  (let [v (* (abs k) (max (sqrt (+ (* x x) (* y y))) rho0))]
                    (/ d (* 0.5 (+ v (sqrt (+ (* v v) 4)))))))}
    :needs-bounds "x and y"
    :corrects? true
    :lipschitz-of (fn [o children]
                    (let [[hx hy] (. children 1 :bounds)]
                      (shear-factor (rad o.angle) (sqrt (+ (* hx hx) (* hy hy))))))
    :class-of bound-class
    :bounds-of (fn [_ children]
                 (let [[hx hy hz] (. children 1 :bounds)
                       r (sqrt (+ (* hx hx) (* hy hy)))]
                   [r r hz]))}
   {:kind :bend :role :point
    :class-doc "bound, Lipschitz from the child's size"
    :doc "Bends its child in the xz plane: :angle degrees of turn per unit along x (Lipschitz factor grows with the child's size)."
    :params [{:name :angle :type :degrees :min -3600 :max 3600 :default 20}]
    :children [1 1]
    :args [{:name :k :type :float} {:name :rho0 :type :float}]
    :pack (fn [o child] (let [[hx _ hz] child.bounds] [(rad o.angle) (sqrt (+ (* hx hx) (* hz hz)))]))
    :glsl-name "opBend"
    :glsl "vec3 opBend(vec3 p, float k, float rho0) {
    float c = cos(k * p.x);
    float s = sin(k * p.x);
    return vec3(c * p.x - s * p.z, p.y, s * p.x + c * p.z);
}"
    :cpu (fn [x y z k]
           (let [c (cos (* k x)) s (sin (* k x))]
             (values (- (* c x) (* s z)) y (+ (* s x) (* c z)))))
    ;; The bent point is R(k x) (x, z): its derivative along x gains k times the
    ;; rotated (x, z), which is not orthogonal to x, so the factor is 1 + k rho (rho
    ;; as for the twist: the largest radius about y on the way to the child).
    :post {:glsl-name "opBendDistance"
           :glsl "float opBendDistance(float d, vec3 p, float k, float rho0) {
    return d / (1.0 + abs(k) * max(length(p.xz), rho0));
}"
           :cpu (fn [d x _ z k rho0]
                  (/ d (+ 1 (* (abs k) (max (sqrt (+ (* x x) (* z z))) rho0)))))}
    :needs-bounds "x and z"
    :corrects? true
    :lipschitz-of (fn [o children]
                    (let [[hx _ hz] (. children 1 :bounds)]
                      (+ 1 (* (abs (rad o.angle)) (sqrt (+ (* hx hx) (* hz hz)))))))
    :class-of bound-class
    :bounds-of (fn [_ children]
                 (let [[hx hy hz] (. children 1 :bounds)
                       r (sqrt (+ (* hx hx) (* hz hz)))]
                   [r hy r]))}
   {:kind :repeat :role :cells
    :class-doc "keeps when the child fits its cell, else bound"
    :doc "Repeats its child forever with :period [x y z] (0: not along that axis); :count [x y z] limits it to 2n+1 copies per axis."
    :params [{:name :period :type :lengths3 :default [2 2 0]}
             {:name :count :type :counts3 :optional? true}]
    :children [1 1]
    :args [{:name :period :type :vec3} {:name :limit :type :vec3}]
    :pack (fn [o] (let [[px py pz] o.period
                        [lx ly lz] (or o.count [-1 -1 -1])]
                    [px py pz lx ly lz]))
    :cells cell-count-of
    :check (fn [o]
             (let [[x y z] o.period]
               (when (= 0 x y z)
                 (values :period "must be above 0 along at least one axis (0 leaves an axis unrepeated)"))))
    :glsl-name "opRepeat"
    :glsl repeat-glsl
    :cpu repeat-cell
    :variant-of (fn [o] (. repeat-variants (repeat-axes o)))
    :own-cell? repeat-own-cell?
    :boxed-neighbours? repeat-boxed-neighbours?
    :class-of (fn [o children] (if (fits-cell? o children) (. children 1 :class) :bound))
    :bounds-of repeat-bounds}
   {:kind :polar :role :cells
    :class-doc "keeps"
    :doc "Repeats its child :count times around the z axis (the child's copy at angle 0 lies along +x)."
    :params [{:name :count :type :count :min 1 :max 256 :default 6}]
    :children [1 1]
    ;; The sector's angle, and its cosine and sine (the turn to a neighbour sector).
    :args [{:name :sector :type :float} {:name :turn :type :vec2}]
    :pack (fn [o] (let [s (/ (* 2 pi) o.count)] [s (cos s) (sin s)]))
    :cells (fn [o] (if (> o.count 1) 2 1))
    ;; From 3 sectors on, the point's angle within its sector is at most 60 degrees
    ;; either way: its sine and cosine by their series there (exact to float), and
    ;; the neighbour sector's point turned from the own one by the sector (llvmpipe's
    ;; sin and cos cost more; colonnade: 6% of a frame). A child symmetric in y (its
    ;; lowered info, read first) is folded into its half sector instead (polar-fold).
    :variant-reads-child? true
    :variant-of (fn [o ?child]
                  (if (and (> o.count 1) (?. ?child :symmetric 2)) (polar-fold o.count)
                      (>= o.count 3) polar-narrow))
    ;; Copies turned about z: symmetric in z as the child is, and in y (the copy at
    ;; angle a mirrored is the one at -a, the child mirrored).
    :keeps-symmetric (fn [_ axis] (not= axis 1))
    :glsl-name "opPolar"
    :glsl "vec3 opPolar(vec3 p, float sector, vec2 turn, int cell) {
    float a = atan(p.y, p.x);
    float id = floor(a / sector + 0.5);
    float side = a - id * sector >= 0.0 ? 1.0 : -1.0;
    id += float(cell) * side;
    float b = a - id * sector;
    float r = length(p.xy);
    return vec3(r * cos(b), r * sin(b), p.z);
}"
    :cpu polar-cell
    :class-of (fn [_ children] (. children 1 :class))
    :bounds-of (fn [_ children]
                 (let [b (. children 1 :bounds)]
                   (when b
                     (let [r (sqrt (+ (* (. b 1) (. b 1)) (* (. b 2) (. b 2))))]
                       [r r (. b 3)]))))}

   ;;; Distance operations
   {:kind :round :role :distance
    :class-doc "keeps"
    :doc "Rounds its child: grows it by :radius."
    :params [{:name :radius :type :positive :default 0.1}]
    :children [1 1]
    :args [{:name :r :type :float}] :pack (fn [o] [o.radius])
    :glsl-name "opRound"
    :glsl "float opRound(float d, vec3 p, float r) {
    return d - r;
}"
    :cpu (fn [d _ _ _ r] (- d r))
    :keeps-even true
    :class-of first-class
    :bounds-of (fn [o children] (grow-bounds (. children 1 :bounds) o.radius))}
   {:kind :onion :role :distance
    :class-doc "keeps"
    :doc "Hollows its child into a shell of :thickness (nest onions for layers)."
    :params [{:name :thickness :type :positive :default 0.05}]
    :children [1 1]
    :args [{:name :t :type :float}] :pack (fn [o] [o.thickness])
    :glsl-name "opOnion"
    :glsl "float opOnion(float d, vec3 p, float t) {
    return abs(d) - t;
}"
    :cpu (fn [d _ _ _ t] (- (abs d) t))
    :keeps-symmetric true
    :class-of first-class
    :bounds-of (fn [o children] (grow-bounds (. children 1 :bounds) o.thickness))}
   {:kind :displace :role :distance
    :class-doc "bound, Lipschitz 1 + a f sqrt 3"
    :doc "Adds :amplitude * sin(fx) sin(fy) sin(fz) with :frequency f to its child's distance (Lipschitz factor 1 + a f sqrt 3)."
    :params [{:name :amplitude :type :positive :default 0.05}
             {:name :frequency :type :positive :default 10}]
    :children [1 1]
    :args [{:name :a :type :float} {:name :f :type :float}]
    :pack (fn [o] [o.amplitude o.frequency])
    :glsl-name "opDisplace"
    :glsl "float opDisplace(float d, vec3 p, float a, float f) {
    return d + a * sin(f * p.x) * sin(f * p.y) * sin(f * p.z);
}"
    :cpu (fn [d x y z a f] (+ d (* a (sin (* f x)) (sin (* f y)) (sin (* f z)))))
    :lipschitz-of (fn [o] (+ 1 (* o.amplitude o.frequency (sqrt 3))))
    :class-of bound-class
    :bounds-of (fn [o children] (grow-bounds (. children 1 :bounds) o.amplitude))}

   ;;; Combinations
   {:kind :union :role :combine
    :class-doc "exact when the children are"
    :doc "Union of its children (exact outside when they are)."
    :params []
    :children [1]
    :args [] :pack (fn [] [])
    :glsl-name "opUnion"
    :glsl "float opUnion(float a, float b) {
    return min(a, b);
}
float wUnion(float a, float b) {
    return a <= b ? 1.0 : 0.0;
}"
    :cpu (fn [a b] (min a b))
    :cpu-weight (fn [a b] (if (<= a b) 1 0))
    :keeps-even true
    :class-of all-exact
    :bounds-of merge-bounds}
   {:kind :intersection :role :combine
    :class-doc "bound"
    :doc "Intersection of its children (a bound)."
    :params []
    :children [2]
    :args [] :pack (fn [] [])
    :glsl-name "opIntersection"
    :glsl "float opIntersection(float a, float b) {
    return max(a, b);
}
float wIntersection(float a, float b) {
    return a >= b ? 1.0 : 0.0;
}"
    :cpu (fn [a b] (max a b))
    :cpu-weight (fn [a b] (if (>= a b) 1 0))
    :keeps-even true
    :class-of bound-class
    :bounds-of (fn [_ children]
                 (var out nil)
                 (each [_ c (ipairs children)]
                   (when c.bounds
                     (set out (if out (icollect [i v (ipairs out)] (min v (. c.bounds i)))
                                  c.bounds))))
                 out)}
   {:kind :subtraction :role :combine
    :class-doc "bound"
    :doc "Its first child with the others cut away; the cut shows the cutter's material (a bound)."
    :params []
    :children [2]
    :args [] :pack (fn [] [])
    :glsl-name "opSubtraction"
    :glsl "float opSubtraction(float a, float b) {
    return max(a, -b);
}
float wSubtraction(float a, float b) {
    return a >= -b ? 1.0 : 0.0;
}"
    :cpu (fn [a b] (max a (- b)))
    :cpu-weight (fn [a b] (if (>= a (- b)) 1 0))
    :class-of bound-class
    :bounds-of first-bounds}
   {:kind :xor :role :combine
    :class-doc "bound"
    :doc "What is inside exactly one of its children (a bound)."
    :params []
    :children [2]
    :args [] :pack (fn [] [])
    :glsl-name "opXor"
    :glsl "float opXor(float a, float b) {
    return max(min(a, b), -max(a, b));
}
float wXor(float a, float b) {
    return min(a, b) >= -max(a, b) ? (a <= b ? 1.0 : 0.0) : (a >= b ? 1.0 : 0.0);
}"
    :cpu (fn [a b] (max (min a b) (- (max a b))))
    :cpu-weight (fn [a b] (if (>= (min a b) (- (max a b)))
                              (if (<= a b) 1 0)
                              (if (>= a b) 1 0)))
    :class-of bound-class
    :bounds-of merge-bounds}
   {:kind :smooth-union :role :combine
    :class-doc "bound"
    :doc "Union blended over :radius (distance units); :kernel :poly (quadratic) or :exp; materials blend by the same weight."
    :params [{:name :radius :type :positive :default 0.25}
             {:name :kernel :type :choice :choices [:poly :exp] :default :poly :structural? true}]
    :children [2]
    :args [{:name :r :type :float}] :pack (fn [o] [o.radius])
    :variants {:poly {:glsl-name "opSmoothUnion"
                      :glsl "float opSmoothUnion(float a, float b, float r) {
    float h = clamp(0.5 + 0.5 * (b - a) / r, 0.0, 1.0);
    return mix(b, a, h) - r * h * (1.0 - h);
}
float wSmoothUnion(float a, float b, float r) {
    return clamp(0.5 + 0.5 * (b - a) / r, 0.0, 1.0);
}"
                      :cpu (fn [a b r]
                             (let [h (max 0 (min 1 (+ 0.5 (/ (* 0.5 (- b a)) r))))]
                               (- (+ b (* (- a b) h)) (* r h (- 1 h)))))
                      :cpu-weight (fn [a b r] (max 0 (min 1 (+ 0.5 (/ (* 0.5 (- b a)) r)))))}
               :exp {:glsl-name "opSmoothUnionExp"
                     :glsl "float opSmoothUnionExp(float a, float b, float r) {
    float m = min(a, b);
    return m - r * log(exp((m - a) / r) + exp((m - b) / r));
}
float wSmoothUnionExp(float a, float b, float r) {
    float m = min(a, b);
    float ea = exp((m - a) / r);
    return ea / (ea + exp((m - b) / r));
}"
                     :cpu (fn [a b r]
                            (let [m (min a b)]
                              (- m (* r (log (+ (exp (/ (- m a) r)) (exp (/ (- m b) r))))))))
                     :cpu-weight (fn [a b r]
                                   (let [m (min a b) ea (exp (/ (- m a) r))]
                                     (/ ea (+ ea (exp (/ (- m b) r))))))}}
    :class-of bound-class
    :bounds-of (fn [o children] (grow-bounds (merge-bounds o children) o.radius))}
   {:kind :smooth-intersection :role :combine
    :class-doc "bound"
    :doc "Intersection blended over :radius (polynomial kernel)."
    :params [{:name :radius :type :positive :default 0.25}]
    :children [2]
    :args [{:name :r :type :float}] :pack (fn [o] [o.radius])
    :glsl-name "opSmoothIntersection"
    :glsl "float opSmoothIntersection(float a, float b, float r) {
    float h = clamp(0.5 - 0.5 * (b - a) / r, 0.0, 1.0);
    return mix(b, a, h) + r * h * (1.0 - h);
}
float wSmoothIntersection(float a, float b, float r) {
    return clamp(0.5 - 0.5 * (b - a) / r, 0.0, 1.0);
}"
    :cpu (fn [a b r]
           (let [h (max 0 (min 1 (- 0.5 (/ (* 0.5 (- b a)) r))))]
             (+ (+ b (* (- a b) h)) (* r h (- 1 h)))))
    :cpu-weight (fn [a b r] (max 0 (min 1 (- 0.5 (/ (* 0.5 (- b a)) r)))))
    :class-of bound-class
    :bounds-of (fn [_ children] (. children 1 :bounds))}
   {:kind :smooth-subtraction :role :combine
    :class-doc "bound"
    :doc "Subtraction blended over :radius (polynomial kernel); the cut shows the cutter's material."
    :params [{:name :radius :type :positive :default 0.25}]
    :children [2]
    :args [{:name :r :type :float}] :pack (fn [o] [o.radius])
    :glsl-name "opSmoothSubtraction"
    :glsl "float opSmoothSubtraction(float a, float b, float r) {
    float h = clamp(0.5 - 0.5 * (a + b) / r, 0.0, 1.0);
    return mix(a, -b, h) + r * h * (1.0 - h);
}
float wSmoothSubtraction(float a, float b, float r) {
    return 1.0 - clamp(0.5 - 0.5 * (a + b) / r, 0.0, 1.0);
}"
    :cpu (fn [a b r]
           (let [h (max 0 (min 1 (- 0.5 (/ (* 0.5 (+ a b)) r))))]
             (+ (+ a (* (- (- b) a) h)) (* r h (- 1 h)))))
    :cpu-weight (fn [a b r] (- 1 (max 0 (min 1 (- 0.5 (/ (* 0.5 (+ a b)) r))))))
    :class-of bound-class
    :bounds-of first-bounds}
   {:kind :chamfer-union :role :combine
    :class-doc "bound"
    :doc "Union with a 45-degree chamfer of :radius where the children meet."
    :params [{:name :radius :type :positive :default 0.25}]
    :children [2]
    :args [{:name :r :type :float}] :pack (fn [o] [o.radius])
    :glsl-name "opChamferUnion"
    :glsl "float opChamferUnion(float a, float b, float r) {
    return min(min(a, b), (a + b - r) * 0.5);
}
float wChamferUnion(float a, float b, float r) {
    return a <= b ? 1.0 : 0.0;
}"
    ;; The chamfer face is a + b = r. Scaled by 1/sqrt 2 its value is the distance to
    ;; that face where the two gradients are orthogonal, but where they are parallel
    ;; it changes sqrt 2 per unit and overshoots; scaled by 1/2 it never does.
    :cpu (fn [a b r] (min (min a b) (* (- (+ a b) r) 0.5)))
    :cpu-weight (fn [a b] (if (<= a b) 1 0))
    :class-of bound-class
    :bounds-of (fn [o children] (grow-bounds (merge-bounds o children) o.radius))}
   {:kind :stairs-union :role :combine
    :class-doc "bound"
    :doc "Union with :steps stair steps over :radius where the children meet."
    :params [{:name :radius :type :positive :default 0.25}
             {:name :steps :type :count :min 1 :max 16 :default 3}]
    :children [2]
    :args [{:name :r :type :float} {:name :n :type :float}]
    :pack (fn [o] [o.radius o.steps])
    :glsl-name "opStairsUnion"
    ;; The corner between the two surfaces filled with n square steps: the union of
    ;; the quarter planes a < (i + 1) s, b < (n - i) s for i = 0 .. n - 1, s = r / n;
    ;; each is max(a - ai, b - bi), a bound, like the union itself.
    :glsl "float opStairsUnion(float a, float b, float r, float n) {
    float s = r / n;
    float d = min(a, b);
    for (float i = 0.0; i < n; i += 1.0) {
        d = min(d, max(a - (i + 1.0) * s, b - (n - i) * s));
    }
    return d;
}
float wStairsUnion(float a, float b, float r, float n) {
    return a <= b ? 1.0 : 0.0;
}"
    :cpu (fn [a b r n]
           (let [s (/ r n)]
             (var d (min a b))
             (for [i 0 (- n 1)]
               (set d (min d (max (- a (* (+ i 1) s)) (- b (* (- n i) s))))))
             d))
    :cpu-weight (fn [a b] (if (<= a b) 1 0))
    :class-of bound-class
    :bounds-of (fn [o children] (grow-bounds (merge-bounds o children) o.radius))}])

(local by-kind (collect [_ d (ipairs operations)] d.kind d))

(fn variant [d o ?child]
  "The GLSL and CPU forms of operation `d` for node `o` (kernel variants; a
repetition's for the axes it repeats along; a polar one's for its child, whose
lowered info `?child` is when `d` has :variant-reads-child?). A form with its own
:args and :pack is packed by them."
  (if d.variants (. d.variants (or o.kernel :poly))
      d.variant-of (or (d.variant-of o ?child) d)
      d))

(fn lookup [kind]
  "The descriptor of operation `kind`, or nil."
  (. by-kind kind))

(fn kind-names []
  "The operation kinds, sorted."
  (doto (icollect [_ d (ipairs operations)] d.kind) table.sort))

{:all operations : lookup : kind-names : variant}

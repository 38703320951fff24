;; The repeat operation (cells): its descriptor, as src/sdf/operations.fnl lists
;; the fields.

(local {: min : max : floor} math)
(local {: round} (require :src.sdf.operation-kit))

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
 :bounds-of repeat-bounds
 ;; Nodes the tests check it on (test/operations_spec.fnl): its promises on each,
 ;; sampled within :extent (half extents about the origin).
 :examples [{:name "repeat" :extent [4 1.5 1.5]
             :node "{:kind :repeat :period [3 0 0] :children [{:kind :sphere :radius 0.5 :pos [0.8 0 0]}]}"}
            {:name "repeat-limited" :extent [8.5 5.5 1.5]
             :node "{:kind :repeat :period [3 3 0] :count [2 1 0] :children [{:kind :box :size [1 1 1]}]}"}]}

;; The polar operation (cells): its descriptor, as src/sdf/operations.fnl lists
;; the fields.

(local {: sqrt : sin : cos : atan2 : pi} math)
(local {: round} (require :src.sdf.operation-kit))

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
                    [r r (. b 3)]))))
 ;; Nodes the tests check it on (test/operations_spec.fnl): its promises on each,
 ;; sampled within :extent (half extents about the origin).
 :examples [{:name "polar" :extent [3 3 1.5]
             :node "{:kind :polar :count 6 :children [{:kind :sphere :radius 0.5 :pos [2 0.3 0]}]}"}]}

;; Adaptive meshes (`--mesh ... --adaptive ERROR`): a dual-contoured mesh made
;; coarser where the surface allows it. Edges collapse one at a time, one end moved
;; onto the other (a half-edge collapse: every vertex left is one the contouring put
;; on the surface), cheapest first by Garland and Heckbert's quadrics (the squared
;; distances to the planes of the triangles each vertex has absorbed). A collapse is
;; taken only if the mesh stays a closed 2-manifold (the link condition), every
;; triangle it changes keeps its side (no normal turned past 60 degrees, none a
;; sliver), stays within ERROR of the field's surface at points spread over it about
;; a cell apart, and crosses no other triangle (the exact test of
;; src/mesh/intersect.fnl, against the triangles near it). A vertex whose neighbours
;; differ from it in colour is kept, so materials keep their borders. Flat faces end
;; as a few large triangles; curved ones keep as many as the error needs; sharp edges
;; and corners stay, since moving them off costs more than ERROR.
;;
;; Pure: runs under plain LuaJIT. The field is a function from a flat list of points
;; to their values (contour's cut field), so the same simplifier serves the CPU and
;; the GPU field.

(local intersect (require :src.mesh.intersect))

(local sqrt math.sqrt)
(local floor math.floor)
(local ceil math.ceil)
(local abs math.abs)
(local min math.min)
(local max math.max)

;; A changed triangle's normal may turn by at most 60 degrees in one collapse: more
;; is a fold in the making (the distance check alone lets a triangle flip over
;; within a thin slab of the surface).
(local min-turn-cos 0.5)
;; The shape of a triangle, 4 sqrt(3) area / (sum of squared sides): 1 for an
;; equilateral one, 0.4 for angles of 20, 20 and 140 degrees or of 12, 84 and 84, 0.1
;; for 5, 5 and 170. A collapse may not make a triangle worse than this (nor worse than
;; the worst it replaces, if that is). At 0.1, machined-part at 128 cells kept 3,162
;; triangles, 29.7% of them with an angle under 10 degrees (the uniform mesh: 0.9%);
;; at 0.4, 5,034 and 1.1%.
(local min-quality 0.4)
;; Points tested on a changed triangle: a barycentric grid of k x k sub-triangles,
;; k its longest side in steps of this many cells (at least 3: the edges' thirds and
;; the centre), at most max-divisions.
(local sample-spacing 2)
(local max-divisions 16)
;; An empty bucket.
(local none {})
;; Colours closer than this per channel are one material's.
(local same-colour 1e-6)

;;; Quadrics: 10 numbers per vertex (the symmetric 4x4 matrix of the planes' sum),
;;; and how many planes each holds.

(fn add-plane! [q base a b c d]
  (tset q (+ base 1) (+ (. q (+ base 1)) (* a a)))
  (tset q (+ base 2) (+ (. q (+ base 2)) (* a b)))
  (tset q (+ base 3) (+ (. q (+ base 3)) (* a c)))
  (tset q (+ base 4) (+ (. q (+ base 4)) (* a d)))
  (tset q (+ base 5) (+ (. q (+ base 5)) (* b b)))
  (tset q (+ base 6) (+ (. q (+ base 6)) (* b c)))
  (tset q (+ base 7) (+ (. q (+ base 7)) (* b d)))
  (tset q (+ base 8) (+ (. q (+ base 8)) (* c c)))
  (tset q (+ base 9) (+ (. q (+ base 9)) (* c d)))
  (tset q (+ base 10) (+ (. q (+ base 10)) (* d d))))

(fn quadric-at [q i j x y z]
  "The sum of squared distances from x y z to the planes of vertices i and j's
quadrics (0-based bases into q)."
  (var s 0)
  (each [_ base (ipairs [i j])]
    (let [a2 (. q (+ base 1)) ab (. q (+ base 2)) ac (. q (+ base 3)) ad (. q (+ base 4))
          b2 (. q (+ base 5)) bc (. q (+ base 6)) bd (. q (+ base 7))
          c2 (. q (+ base 8)) cd (. q (+ base 9)) d2 (. q (+ base 10))]
      (set s (+ s (* a2 x x) (* b2 y y) (* c2 z z)
                (* 2 (+ (* ab x y) (* ac x z) (* bc y z)))
                (* 2 (+ (* ad x) (* bd y) (* cd z)))
                d2))))
  (max s 0))

;;; A binary heap of candidate collapses: cost, from, to and both ends' stamps at
;;; the time (a vertex's stamp changes with its quadric, so stale entries are known
;;; when popped).

(fn heap-push! [h cost u v su sv]
  (set h.n (+ h.n 1))
  (var i h.n)
  (var done? false)
  (while (and (> i 1) (not done?))
    (let [parent (floor (/ i 2))]
      (if (< cost (. h.cost parent))
          (do (tset h.cost i (. h.cost parent)) (tset h.u i (. h.u parent))
              (tset h.v i (. h.v parent)) (tset h.su i (. h.su parent))
              (tset h.sv i (. h.sv parent))
              (set i parent))
          (set done? true))))
  (tset h.cost i cost) (tset h.u i u) (tset h.v i v) (tset h.su i su) (tset h.sv i sv))

(fn heap-pop! [h]
  "The cheapest candidate as cost u v su sv, removed from `h`."
  (let [cost (. h.cost 1) u (. h.u 1) v (. h.v 1) su (. h.su 1) sv (. h.sv 1)
        n h.n
        lc (. h.cost n) lu (. h.u n) lv (. h.v n) lsu (. h.su n) lsv (. h.sv n)]
    (set h.n (- n 1))
    (var i 1)
    (var done? (<= h.n 1))
    (while (not done?)
      (let [l (* 2 i) r (+ l 1)
            c (if (and (<= r h.n) (< (. h.cost r) (. h.cost l))) r l)]
        (if (and (<= c h.n) (< (. h.cost c) lc))
            (do (tset h.cost i (. h.cost c)) (tset h.u i (. h.u c)) (tset h.v i (. h.v c))
                (tset h.su i (. h.su c)) (tset h.sv i (. h.sv c))
                (set i c))
            (set done? true))))
    (when (>= h.n 1)
      (tset h.cost i lc) (tset h.u i lu) (tset h.v i lv) (tset h.su i lsu) (tset h.sv i lsv))
    (values cost u v su sv)))

;;; The state: positions and triangles (flat, 1-based vertices as the mesher writes
;;; them), each vertex's triangles (0-based), quadrics, stamps, and a hash of the
;;; triangles by cells of space for the crossing test.

(fn new-state [m colors error h values-of]
  (let [p m.positions
        tris m.triangles
        nv (/ (length p) 3)
        nt (/ (length tris) 3)
        q []
        planes []
        vt []
        s {:p p :tris tris :colors colors :nv nv :nt nt :q q :planes planes :vt vt
           :stamp [] :gone [] :dead [] :e error :h h :values-of values-of
           :heap {:n 0 :cost [] :u [] :v [] :su [] :sv []}
           :seen [] :near [] :around [] :mark 0
           ;; Tables reused from test to test (each collapse tried would otherwise
           ;; leave a few dozen behind; the collector's full cycles over the mesh
           ;; took a quarter of the time at 256 cells).
           :scratch-edges [] :scratch-normals [] :scratch-corners [] :scratch-boxes []
           :stats {:collapsed 0 :far 0 :folded 0 :crossed 0 :manifold 0 :colour 0
                   :points 0}}]
    (for [i 1 (* 10 nv)] (tset q i 0))
    (for [v 1 nv] (tset planes v 0) (tset vt v []) (tset s.stamp v 0))
    (for [t 0 (- nt 1)]
      (let [a (. tris (+ (* 3 t) 1)) b (. tris (+ (* 3 t) 2)) c (. tris (+ (* 3 t) 3))
            ax (. p (- (* 3 a) 2)) ay (. p (- (* 3 a) 1)) az (. p (* 3 a))
            ux (- (. p (- (* 3 b) 2)) ax) uy (- (. p (- (* 3 b) 1)) ay) uz (- (. p (* 3 b)) az)
            wx (- (. p (- (* 3 c) 2)) ax) wy (- (. p (- (* 3 c) 1)) ay) wz (- (. p (* 3 c)) az)
            nx (- (* uy wz) (* uz wy)) ny (- (* uz wx) (* ux wz)) nz (- (* ux wy) (* uy wx))
            l (sqrt (+ (* nx nx) (* ny ny) (* nz nz)))]
        (each [_ v (ipairs [a b c])]
          (table.insert (. vt v) t)
          (when (> l 0)
            (let [nx (/ nx l) ny (/ ny l) nz (/ nz l)]
              (add-plane! q (* 10 (- v 1)) nx ny nz (- (+ (* nx ax) (* ny ay) (* nz az))))
              (tset planes v (+ 1 (. planes v))))))))
    ;; The hash's cells: three mesh cells a side (machined-part at 128 cells: 5.1 s of
    ;; CPU for the whole export at 3, 5.4 at 2, 6.9 at 4).
    (set s.cell (* 3 h))
    (set s.buckets {})
    (set s.ranges [])
    (set s.boxes [])
    s))

(fn corner [s t k u v]
  "Corner k (1-3) of triangle t (0-based), with vertex u read as v."
  (let [w (. s.tris (+ (* 3 t) k))]
    (if (= w u) v w)))

(fn hash-range [s x0 x1]
  (values (floor (/ x0 s.cell)) (floor (/ x1 s.cell))))

(fn cell-key [i j k]
  ;; Cells within 2^16 of the origin each way (of four mesh cells: a mesh of 262,144
  ;; cells a side), so the key stays under 2^51, exact in a double.
  (+ (+ i 65536) (* 131072 (+ (+ j 65536) (* 131072 (+ k 65536))))))

(fn triangle-box [s t u v]
  (let [p s.p
        a (corner s t 1 u v) b (corner s t 2 u v) c (corner s t 3 u v)
        ax (. p (- (* 3 a) 2)) ay (. p (- (* 3 a) 1)) az (. p (* 3 a))
        bx (. p (- (* 3 b) 2)) by (. p (- (* 3 b) 1)) bz (. p (* 3 b))
        cx (. p (- (* 3 c) 2)) cy (. p (- (* 3 c) 1)) cz (. p (* 3 c))]
    (values (min ax bx cx) (min ay by cy) (min az bz cz)
            (max ax bx cx) (max ay by cy) (max az bz cz))))

(fn in-range? [r o i j k]
  (and (<= (. r (+ o 1)) i (. r (+ o 2))) (<= (. r (+ o 3)) j (. r (+ o 4)))
       (<= (. r (+ o 5)) k (. r (+ o 6)))))

(fn hash-insert! [s t]
  "Hash triangle t (0-based) by the cells its box covers, adding it to those it did
not cover before (an entry left in a cell the box has left is dropped when next
met, see live-entry?); its box is kept for the crossing test."
  (let [(lx ly lz hx hy hz) (triangle-box s t)
        (i0 i1) (hash-range s lx hx) (j0 j1) (hash-range s ly hy) (k0 k1) (hash-range s lz hz)
        r s.ranges o (* 6 t)
        b s.boxes
        before? (not= nil (. r (+ o 1)))
        old (when before? [(. r (+ o 1)) (. r (+ o 2)) (. r (+ o 3)) (. r (+ o 4))
                           (. r (+ o 5)) (. r (+ o 6))])]
    (tset r (+ o 1) i0) (tset r (+ o 2) i1) (tset r (+ o 3) j0) (tset r (+ o 4) j1)
    (tset r (+ o 5) k0) (tset r (+ o 6) k1)
    (tset b (+ o 1) lx) (tset b (+ o 2) ly) (tset b (+ o 3) lz)
    (tset b (+ o 4) hx) (tset b (+ o 5) hy) (tset b (+ o 6) hz)
    (for [k k0 k1]
      (for [j j0 j1]
        (for [i i0 i1]
          (when (not (and before? (in-range? old 0 i j k)))
            (let [key (cell-key i j k)
                  list (. s.buckets key)]
              (if list (tset list (+ 1 (length list)) t) (tset s.buckets key [t])))))))))

(fn live-entry? [s t i j k]
  ;; Whether triangle t, met in cell i j k's bucket, is alive and still covers it.
  (and (not (. s.dead (+ t 1))) (in-range? s.ranges (* 6 t) i j k)))

(fn points-of [s t u v out]
  ;; Triangle t's corners (u read as v) as [x y z x y z x y z].
  (for [k 1 3]
    (let [w (corner s t k u v)]
      (for [c 1 3] (tset out (+ (* 3 (- k 1)) c) (. s.p (+ (* 3 (- w 1)) c))))))
  out)

;;; The tests of one collapse, u onto v.

(fn colour-kept? [s u]
  ;; Every neighbour of u has u's colour.
  (let [c s.colors]
    (if (not c) true
        (accumulate [ok? true _ t (ipairs (. s.vt u)) &until (not ok?)]
          (faccumulate [ok? ok? k 1 3 &until (not ok?)]
            (let [w (. s.tris (+ (* 3 t) k))]
              (and (< (abs (- (. c (- (* 3 w) 2)) (. c (- (* 3 u) 2)))) same-colour)
                   (< (abs (- (. c (- (* 3 w) 1)) (. c (- (* 3 u) 1)))) same-colour)
                   (< (abs (- (. c (* 3 w)) (. c (* 3 u)))) same-colour))))))))

(fn neighbours [s u]
  "The vertices sharing an edge with u, each once."
  (let [found []
        mark (do (set s.mark (+ s.mark 1)) s.mark)]
    (each [_ t (ipairs (. s.vt u))]
      (for [k 1 3]
        (let [w (. s.tris (+ (* 3 t) k))]
          (when (and (not= w u) (not= mark (. s.near w)))
            (tset s.near w mark)
            (tset found (+ 1 (length found)) w)))))
    found))

(fn link-kept? [s u v]
  "The link condition for collapsing edge u-v of a closed manifold: u and v share
exactly two neighbours (the far corners of the edge's two triangles), neither of
which is left with fewer than three triangles."
  (let [token (do (set s.mark (+ s.mark 1)) s.mark)]
    (each [_ w (ipairs (neighbours s v))] (tset s.around w token))
    (var (common ok?) (values 0 (= token (. s.around u))))
    (each [_ w (ipairs (neighbours s u)) &until (not ok?)]
      (when (and (not= w v) (= token (. s.around w)))
        (set common (+ common 1))
        (when (<= (length (. s.vt w)) 3) (set ok? false))))
    (and ok? (= common 2))))

(fn normal-of [s t u v]
  (let [p s.p
        a (corner s t 1 u v) b (corner s t 2 u v) c (corner s t 3 u v)
        ax (. p (- (* 3 a) 2)) ay (. p (- (* 3 a) 1)) az (. p (* 3 a))
        ux (- (. p (- (* 3 b) 2)) ax) uy (- (. p (- (* 3 b) 1)) ay) uz (- (. p (* 3 b)) az)
        wx (- (. p (- (* 3 c) 2)) ax) wy (- (. p (- (* 3 c) 1)) ay) wz (- (. p (* 3 c)) az)
        vx (- wx ux) vy (- wy uy) vz (- wz uz)
        sides (+ (* ux ux) (* uy uy) (* uz uz) (* wx wx) (* wy wy) (* wz wz)
                 (* vx vx) (* vy vy) (* vz vz))
        nx (- (* uy wz) (* uz wy)) ny (- (* uz wx) (* ux wz)) nz (- (* ux wy) (* uy wx))
        l (sqrt (+ (* nx nx) (* ny ny) (* nz nz)))]
    ;; The normal (length twice the area) and the shape, 4 sqrt(3) area / sides.
    (values nx ny nz l (if (> sides 0) (/ (* 2 (sqrt 3) l) sides) 0))))

(fn shapes-kept? [s u v changed]
  ;; No changed triangle turns by more than min-turn's angle or becomes a sliver.
  (var worst math.huge)
  (each [_ t (ipairs changed)]
    (let [(_ _ _ _ q) (normal-of s t 0 0)]
      (set worst (min worst q))))
  (let [floor-q (min min-quality worst)]
    (accumulate [ok? true _ t (ipairs changed) &until (not ok?)]
      (let [(ax ay az al) (normal-of s t 0 0)
            (bx by bz bl q) (normal-of s t u v)]
        (and (> bl 0) (> al 0) (>= q floor-q)
             (>= (+ (* ax bx) (* ay by) (* az bz)) (* min-turn-cos al bl)))))))

(fn add-point! [flat p a b c wa wb wc]
  (let [n (length flat)]
    (for [q 1 3]
      (tset flat (+ n q) (+ (* wa (. p (+ (* 3 (- a 1)) q))) (* wb (. p (+ (* 3 (- b 1)) q)))
                            (* wc (. p (+ (* 3 (- c 1)) q))))))))

(fn divisions [p a b h]
  ;; Steps of sample-spacing cells along a b, at least 2 and at most max-divisions.
  (let [d (sqrt (+ (^ (- (. p (- (* 3 b) 2)) (. p (- (* 3 a) 2))) 2)
                   (^ (- (. p (- (* 3 b) 1)) (. p (- (* 3 a) 1))) 2)
                   (^ (- (. p (* 3 b)) (. p (* 3 a))) 2)))]
    (min max-divisions (max 2 (ceil (/ d (* sample-spacing h)))))))

(fn near-surface? [s u v changed]
  "Whether every changed triangle (u read as v) is within the error of the surface
at points about sample-spacing cells apart: inside each triangle (a barycentric
grid, at least its centre) and along each edge the collapse makes (v to a former
neighbour of u alone; the other edges keep their ends), and at its corners (the
mesher's vertices, whose distances were read once: one it placed farther than the
error, at a sharp feature it clamped, keeps its triangles as they are)."
  (let [p s.p
        flat []
        token (do (set s.mark (+ s.mark 1)) s.mark)
        e s.e
        off s.off]
    ;; v's neighbours before the collapse: their edges to v do not change.
    (each [_ w (ipairs (neighbours s v))] (tset s.around w token))
    (var near? true)
    (each [_ t (ipairs changed) &until (not near?)]
      (let [a (corner s t 1 u v) b (corner s t 2 u v) c (corner s t 3 u v)
            k (max 3 (divisions p a b s.h) (divisions p b c s.h) (divisions p c a s.h))]
        (set near? (and (<= (. off a) e) (<= (. off b) e) (<= (. off c) e)))
        (for [i 1 (- k 2)]
          (for [j 1 (- k i 1)]
            (add-point! flat p a b c (/ i k) (/ j k) (/ (- k i j) k))))
        (each [_ w (ipairs [a b c])]
          (when (and (not= w v) (not= token (. s.around w)))
            (tset s.around w token)
            (let [m (divisions p v w s.h)]
              (for [i 1 (- m 1)]
                (add-point! flat p v w v (/ i m) (- 1 (/ i m)) 0)))))))
    (and near?
         (let [ds (s.values-of flat)]
           (set s.stats.points (+ s.stats.points (length ds)))
           (accumulate [ok? true _ d (ipairs ds) &until (not ok?)]
             (<= (abs d) e))))))

(fn apart-along? [tp op shared-t shared-o tol ax ay az]
;; See separated?: whether axis a parts the two triangles.
    (let [l (sqrt (+ (* ax ax) (* ay ay) (* az az)))]
      (if (<= l 0) false
          (let [gap (* tol l)]
            (var (t-lo t-hi o-lo o-hi) (values math.huge (- math.huge) math.huge (- math.huge)))
            (var c nil)
            (for [k 0 2]
              (let [d (+ (* ax (. tp (+ (* 3 k) 1))) (* ay (. tp (+ (* 3 k) 2))) (* az (. tp (+ (* 3 k) 3))))]
                (if (= (+ k 1) shared-t) (set c d)
                    (set (t-lo t-hi) (values (min t-lo d) (max t-hi d))))))
            (for [k 0 2]
              (let [d (+ (* ax (. op (+ (* 3 k) 1))) (* ay (. op (+ (* 3 k) 2))) (* az (. op (+ (* 3 k) 3))))]
                (when (not= (+ k 1) shared-o)
                  (set (o-lo o-hi) (values (min o-lo d) (max o-hi d))))))
            ;; With a shared corner at c: one triangle on its side of c (its
            ;; other corners may lie on the axis's plane through c), the other
            ;; strictly beyond; they meet only at the corner.
            (if c
                (or (and (<= t-hi (+ c gap)) (> o-lo (+ c gap)))
                    (and (< t-hi (- c gap)) (>= o-lo (- c gap)))
                    (and (>= t-lo (- c gap)) (< o-hi (- c gap)))
                    (and (> t-lo (+ c gap)) (<= o-hi (+ c gap))))
                (or (< t-hi (- o-lo gap)) (< o-hi (- t-lo gap))))))))

(fn separated? [tp op shared-t shared-o tol e n]
  "Whether some axis (either triangle's normal, an edge of one crossed with an edge
of the other, or an edge crossed with a normal: the separating axes of two
triangles) has triangle tp's corners on one side and op's on the other, each
beyond `tol` times the axis's length except a corner they share (shared-t and
shared-o: its index 1-3 in each, or 0). Then they meet at most in that corner.
`e` and `n` are tables to work in (the edges and normals)."
  (do
    (for [q 0 1]
      (let [x (if (= q 0) tp op) o (* 9 q)]
        (for [k 0 2]
          (let [a (* 3 k) b (* 3 (% (+ k 1) 3))]
            (for [c 1 3] (tset e (+ o a c) (- (. x (+ b c)) (. x (+ a c)))))))
        (tset n (+ (* 3 q) 1) (- (* (. e (+ o 2)) (. e (+ o 6))) (* (. e (+ o 3)) (. e (+ o 5)))))
        (tset n (+ (* 3 q) 2) (- (* (. e (+ o 3)) (. e (+ o 4))) (* (. e (+ o 1)) (. e (+ o 6)))))
        (tset n (+ (* 3 q) 3) (- (* (. e (+ o 1)) (. e (+ o 5))) (* (. e (+ o 2)) (. e (+ o 4)))))))
    (var found? false)
    (for [q 0 1 &until found?]
      (set found? (apart-along? tp op shared-t shared-o tol (. n (+ (* 3 q) 1)) (. n (+ (* 3 q) 2)) (. n (+ (* 3 q) 3)))))
    (for [i 0 2 &until found?]
      (for [j 0 2 &until found?]
        (let [ax (. e (+ (* 3 i) 1)) ay (. e (+ (* 3 i) 2)) az (. e (+ (* 3 i) 3))
              bx (. e (+ 9 (* 3 j) 1)) by (. e (+ 9 (* 3 j) 2)) bz (. e (+ 9 (* 3 j) 3))]
          (set found? (apart-along? tp op shared-t shared-o tol (- (* ay bz) (* az by)) (- (* az bx) (* ax bz))
                                    (- (* ax by) (* ay bx)))))))
    ;; In-plane axes, for (nearly) coplanar triangles: each edge crossed with the
    ;; other triangle's normal and its own.
    (for [q 0 1 &until found?]
      (for [i 0 5 &until found?]
        (let [ex (. e (+ (* 3 i) 1)) ey (. e (+ (* 3 i) 2)) ez (. e (+ (* 3 i) 3))
              nx (. n (+ (* 3 q) 1)) ny (. n (+ (* 3 q) 2)) nz (. n (+ (* 3 q) 3))]
          (set found? (apart-along? tp op shared-t shared-o tol (- (* ey nz) (* ez ny)) (- (* ez nx) (* ex nz))
                                    (- (* ex ny) (* ey nx)))))))
    found?))

(fn shared-corners [s t u v o ou ov]
  "How many corners triangles t and o (each with its u read as v: ou ov for o) share,
and the index (1-3) in each of the last one found."
  (var (shared st so) (values 0 0 0))
  (for [i 1 3]
    (for [j 1 3]
      (when (= (corner s t i u v) (corner s o j ou ov))
        (set (shared st so) (values (+ shared 1) i j)))))
  (values shared st so))

(fn meet? [s tp t u v o ou ov op tol]
  ;; Whether t and o cross or fold onto each other: not when they share an edge (they
  ;; meet along it) or a separating axis parts them; else by the exact test.
  (let [(shared st so) (shared-corners s t u v o ou ov)]
    (and (< shared 2)
         (not (separated? tp op st so 1e-9 s.scratch-edges s.scratch-normals))
         (> (intersect.pair-overlap tp op) tol))))

(fn crosses-none? [s u v changed removed]
  "Whether no changed triangle (u read as v) crosses or folds onto another triangle
that it shares no edge with: the changed ones among themselves, then every triangle
hashed in the cells of their joint box, met once, against each changed one whose
box it overlaps."
  (let [tol (* 1e-6 s.h)
        n (length changed)
        corners s.scratch-corners
        boxes s.scratch-boxes]
    (var (lx ly lz hx hy hz) (values math.huge math.huge math.huge
                                     (- math.huge) (- math.huge) (- math.huge)))
    (each [m t (ipairs changed)]
      (when (not (. corners m)) (tset corners m []) (tset boxes m []))
      (points-of s t u v (. corners m))
      (let [(ax ay az bx by bz) (triangle-box s t u v)
            box (. boxes m)]
        (tset box 1 ax) (tset box 2 ay) (tset box 3 az)
        (tset box 4 bx) (tset box 5 by) (tset box 6 bz)
        (set (lx ly lz) (values (min lx ax) (min ly ay) (min lz az)))
        (set (hx hy hz) (values (max hx bx) (max hy by) (max hz bz)))))
    (var clear? true)
    ;; The changed triangles against each other: they all hold v, so only a fold
    ;; (more than v in common) counts.
    (for [a 1 n &until (not clear?)]
      (for [b (+ a 1) n &until (not clear?)]
        (when (meet? s (. corners a) (. changed a) u v (. changed b) u v (. corners b) tol)
          (set clear? false))))
    (let [mark (do (set s.mark (+ s.mark 1)) s.mark)
          (i0 i1) (hash-range s lx hx) (j0 j1) (hash-range s ly hy) (k0 k1) (hash-range s lz hz)
          op []
          bx s.boxes]
      (each [_ r (ipairs removed)] (tset s.seen (+ r 1) mark))
      (each [_ c (ipairs changed)] (tset s.seen (+ c 1) mark))
      (for [k k0 k1 &until (not clear?)]
        (for [j j0 j1 &until (not clear?)]
          (for [i i0 i1 &until (not clear?)]
            (let [list (or (. s.buckets (cell-key i j k)) none)]
              (var at 1)
              (while (and clear? (<= at (length list)))
                (let [o (. list at)]
                  (if (not (live-entry? s o i j k))
                      ;; Dropped: the last entry takes its place.
                      (let [last (length list)]
                        (tset list at (. list last))
                        (tset list last nil))
                      (do
                        (set at (+ at 1))
                        (when (not= mark (. s.seen (+ o 1)))
                          (tset s.seen (+ o 1) mark)
                          (let [ob (* 6 o)
                                olx (. bx (+ ob 1)) oly (. bx (+ ob 2)) olz (. bx (+ ob 3))
                                ohx (. bx (+ ob 4)) ohy (. bx (+ ob 5)) ohz (. bx (+ ob 6))]
                            (var filled? false)
                            (for [m 1 n &until (not clear?)]
                              (let [[ax ay az bx2 by2 bz2] (. boxes m)]
                                (when (and (<= (max ax olx) (min bx2 ohx))
                                           (<= (max ay oly) (min by2 ohy))
                                           (<= (max az olz) (min bz2 ohz)))
                                  (when (not filled?)
                                    (points-of s o 0 0 op)
                                    (set filled? true))
                                  (when (meet? s (. corners m) (. changed m) u v o 0 0 op tol)
                                    (set clear? false)))))))))))))))
      clear?)))

;;; Collapsing.

(fn consider! [s u v]
  ;; Push u onto v unless the planes u and v hold are already farther than the
  ;; error from v on average (then some of them certainly are).
  (let [p s.p
        x (. p (- (* 3 v) 2)) y (. p (- (* 3 v) 1)) z (. p (* 3 v))
        cost (quadric-at s.q (* 10 (- u 1)) (* 10 (- v 1)) x y z)
        planes (+ (. s.planes u) (. s.planes v))
        e s.e]
    (when (<= cost (* e e planes))
      ;; Ties (a flat face costs 0) go to the shorter edge.
      (let [dx (- (. p (- (* 3 u) 2)) x) dy (- (. p (- (* 3 u) 1)) y) dz (- (. p (* 3 u)) z)
            len2 (+ (* dx dx) (* dy dy) (* dz dz))]
        (heap-push! s.heap (+ cost (* 1e-6 len2)) u v (. s.stamp u) (. s.stamp v))))))

(fn consider-around! [s v]
  (each [_ w (ipairs (neighbours s v))]
    (consider! s w v)
    (consider! s v w)))

(fn collapse! [s u v]
  "Collapse u onto v if every test passes; true if it did."
  (let [removed [] changed []]
    (each [_ t (ipairs (. s.vt u))]
      (if (or (= v (. s.tris (+ (* 3 t) 1))) (= v (. s.tris (+ (* 3 t) 2)))
              (= v (. s.tris (+ (* 3 t) 3))))
          (table.insert removed t)
          (table.insert changed t)))
    (if (not (colour-kept? s u)) (do (set s.stats.colour (+ s.stats.colour 1)) false)
        (or (not= 2 (length removed)) (not (link-kept? s u v)))
        (do (set s.stats.manifold (+ s.stats.manifold 1)) false)
        (not (shapes-kept? s u v changed)) (do (set s.stats.folded (+ s.stats.folded 1)) false)
        (not (near-surface? s u v changed)) (do (set s.stats.far (+ s.stats.far 1)) false)
        (not (crosses-none? s u v changed removed))
        (do (set s.stats.crossed (+ s.stats.crossed 1)) false)
        (do
          ;; The two triangles of the edge go; the others of u take v.
          (each [_ t (ipairs removed)]
            (tset s.dead (+ t 1) true)
            (for [k 1 3]
              (let [w (. s.tris (+ (* 3 t) k))]
                (when (not= w u)
                  (let [list (. s.vt w)]
                    (for [i (length list) 1 -1]
                      (when (= t (. list i)) (table.remove list i))))))))
          (each [_ t (ipairs changed)]
            (for [k 1 3]
              (when (= u (. s.tris (+ (* 3 t) k))) (tset s.tris (+ (* 3 t) k) v)))
            (table.insert (. s.vt v) t)
            (hash-insert! s t))
          (let [q s.q bu (* 10 (- u 1)) bv (* 10 (- v 1))]
            (for [i 1 10] (tset q (+ bv i) (+ (. q (+ bv i)) (. q (+ bu i))))))
          (tset s.planes v (+ (. s.planes v) (. s.planes u)))
          (tset s.vt u [])
          (tset s.gone u true)
          (tset s.stamp v (+ 1 (. s.stamp v)))
          (set s.stats.collapsed (+ s.stats.collapsed 1))
          true))))

(fn compact [s]
  ;; The vertices left, renumbered in order, and the live triangles.
  (let [index [] positions [] colors (when s.colors []) triangles []]
    (var n 0)
    (for [v 1 s.nv]
      (when (not (. s.gone v))
        (set n (+ n 1))
        (tset index v n)
        (for [c 1 3]
          (tset positions (+ (* 3 (- n 1)) c) (. s.p (+ (* 3 (- v 1)) c)))
          (when colors (tset colors (+ (* 3 (- n 1)) c) (. s.colors (+ (* 3 (- v 1)) c)))))))
    (for [t 0 (- s.nt 1)]
      (when (not (. s.dead (+ t 1)))
        (for [k 1 3]
          (table.insert triangles (. index (. s.tris (+ (* 3 t) k)))))))
    {: positions : triangles : colors}))

(fn simplify [m error h values-of ?progress]
  "Mesh `m` ({:positions :triangles :colors}, closed and 2-manifold, as contour.mesh
makes it) with edges collapsed while every triangle stays within `error` of the
surface of `values-of` (fn [flat] -> the field's values at the points of the flat
list x y z ...), a cell of side `h` apart. `?progress` (fn [done total]) hears of
the work now and then. Returns the new mesh (its own tables; `m` is left as it
was) and stats {:before :after (triangles) :error :collapsed :points (field values read)
and the collapses refused, by test: :colour :manifold :folded :far :crossed}."
  (let [tris (icollect [_ v (ipairs m.triangles)] v)
        s (new-state {:positions m.positions :triangles tris} m.colors error h values-of)
        progress (or ?progress (fn []))]
    (progress 0 s.nt)
    ;; Each vertex's distance from the surface, once.
    (set s.off (icollect [_ d (ipairs (values-of m.positions))] (abs d)))
    (set s.stats.points (+ s.stats.points s.nv))
    (for [t 0 (- s.nt 1)] (hash-insert! s t))
    (for [u 1 s.nv]
      (each [_ w (ipairs (neighbours s u))] (consider! s u w)))
    (var tried 0)
    (while (> s.heap.n 0)
      (let [(_ u v su sv) (heap-pop! s.heap)]
        (when (and (not (. s.gone u)) (not (. s.gone v))
                   (= su (. s.stamp u)) (= sv (. s.stamp v)))
          (set tried (+ tried 1))
          (when (= 0 (% tried 4096)) (progress (* 2 s.stats.collapsed) s.nt))
          (when (collapse! s u v)
            (consider-around! s v)))))
    (let [out (compact s)]
      (set s.stats.before s.nt)
      (set s.stats.error error)
      (set s.stats.after (/ (length out.triangles) 3))
      (values out s.stats))))

{: simplify}

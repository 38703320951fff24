;; Self-intersections of a triangle mesh: pairs of triangles that cross each other
;; (issue 46). A uniform grid of boxes finds the pairs whose bounding boxes overlap
;; (the broad phase); each such pair gets an exact test in double precision (the
;; narrow phase, after Möller's "A fast triangle-triangle intersection test": each
;; triangle is cut by the other's plane, and the two cuts, both on the line where the
;; planes meet, overlap or not). What is counted is the length of the part the two
;; triangles have in common: a pair that only touches at a point has none, a pair
;; that crosses has a segment, a coplanar pair that overlaps has an area (its
;; diameter is taken as the length). A mesh is {:positions [x y z ...] :triangles [a
;; b c ...]} (1-based vertex indices). Pure: runs under plain LuaJIT.

;; `pairs` under another name: a loop over `pairs` by that name is LuaJIT's ITERN,
;; which Debian 12's LuaJIT ends early once despecialised (see src/util/wire.fnl).
(local each-pair pairs)

(local {: int-array : float-array} (require :src.util.arrays))

(local sqrt math.sqrt)
(local floor math.floor)
(local abs math.abs)
(local min math.min)
(local max math.max)

;; Triangles (or vertices) between calls of a check's :tick (a mesh at 512 cells has
;; a million triangles and took seconds).
(local tick-every 65536)

;; A vertex nearer a plane than this share of the triangles' size is on it: the
;; distances are sums of products of coordinates, good to some 1e-16 of their size,
;; so 1e-12 takes rounding for zero and nothing a mesher would make on purpose.
(local on-plane 1e-12)

(fn sub [ax ay az bx by bz] (values (- ax bx) (- ay by) (- az bz)))

(fn cross [ax ay az bx by bz]
  (values (- (* ay bz) (* az by)) (- (* az bx) (* ax bz)) (- (* ax by) (* ay bx))))

(fn dot [ax ay az bx by bz] (+ (* ax bx) (* ay by) (* az bz)))

(fn plane-cut [p d]
  "The points where the triangle `p` ([x y z x y z x y z]) meets a plane, its
vertices' signed distances from it being `d` ([d1 d2 d3], zero meaning on it): a
flat list of points [x y z ...] (one: touching at a vertex; two: a segment; none:
clear of it). Not for a triangle in the plane."
  (let [out []]
    (for [i 1 3]
      (let [j (+ 1 (% i 3))
            di (. d i) dj (. d j)
            bi (* 3 (- i 1)) bj (* 3 (- j 1))]
        (when (= di 0)
          (for [q 1 3] (table.insert out (. p (+ bi q)))))
        (when (or (and (< di 0) (> dj 0)) (and (> di 0) (< dj 0)))
          (let [t (/ di (- di dj))]
            (for [q 1 3]
              (table.insert out (+ (. p (+ bi q)) (* t (- (. p (+ bj q)) (. p (+ bi q)))))))))))
    out))

;;; The coplanar case: both triangles in the plane of the first, projected on the
;;; coordinate plane where it is largest, the first clipped by the second (Sutherland
;;; and Hodgman).

(fn clip-polygon [poly ax ay bx by sgn]
  "`poly` (a flat list [u v ...]) clipped to the side of the line a->b where
points with sgn * cross > 0 lie (the inside of a triangle wound with sign sgn)."
  (let [out []
        n (/ (length poly) 2)
        side (fn [u v] (* sgn (- (* (- bx ax) (- v ay)) (* (- by ay) (- u ax)))))]
    (for [i 1 n]
      (let [j (+ 1 (% i n))
            ui (. poly (- (* 2 i) 1)) vi (. poly (* 2 i))
            uj (. poly (- (* 2 j) 1)) vj (. poly (* 2 j))
            si (side ui vi) sj (side uj vj)]
        (when (>= si 0) (table.insert out ui) (table.insert out vi))
        (when (or (and (> si 0) (< sj 0)) (and (< si 0) (> sj 0)))
          (let [t (/ si (- si sj))]
            (table.insert out (+ ui (* t (- uj ui))))
            (table.insert out (+ vi (* t (- vj vi))))))))
    out))

(fn coplanar-overlap [p q nx ny nz scale]
  "The diameter of the overlap of triangles `p` and `q` lying in one plane of
normal n (0 when they are apart or only touch, at a point or along a segment;
`scale` is their size)."
  (let [ax (abs nx) ay (abs ny) az (abs nz)
        ;; Drop the largest coordinate of the normal (w); keep the other two (u v).
        (iu iv iw) (if (and (>= ax ay) (>= ax az)) (values 2 3 1)
                       (>= ay az) (values 3 1 2)
                       (values 1 2 3))
        proj (fn [t] (fcollect [k 0 5] (. t (+ (* 3 (floor (/ k 2))) (if (= 0 (% k 2)) iu iv)))))
        pp (proj p) qp (proj q)
        area2 (fn [t] (- (* (- (. t 3) (. t 1)) (- (. t 6) (. t 2)))
                         (* (- (. t 4) (. t 2)) (- (. t 5) (. t 1)))))
        sgn (if (>= (area2 qp) 0) 1 -1)]
    (var poly pp)
    (for [e 0 2 &until (= 0 (length poly))]
      (let [f (% (+ e 1) 3)]
        (set poly (clip-polygon poly (. qp (+ 1 (* 2 e))) (. qp (+ 2 (* 2 e)))
                                (. qp (+ 1 (* 2 f))) (. qp (+ 2 (* 2 f))) sgn))))
    ;; The overlap's corners back in the plane (the coordinate dropped, from the
    ;; plane's equation through p's first vertex), to measure it there.
    (let [n (/ (length poly) 2)
          nn [nx ny nz]
          w (fn [u v] (- (. p iw) (/ (+ (* (. nn iu) (- u (. p iu))) (* (. nn iv) (- v (. p iv))))
                                     (. nn iw))))
          ws (fcollect [i 1 n] (w (. poly (- (* 2 i) 1)) (. poly (* 2 i))))]
      (var (d area) (values 0 0))
      (for [i 1 n]
        (let [j (+ 1 (% i n))]
          (set area (+ area (- (* (. poly (- (* 2 i) 1)) (. poly (* 2 j)))
                               (* (. poly (- (* 2 j) 1)) (. poly (* 2 i)))))))
        (for [j (+ i 1) n]
          (let [du (- (. poly (- (* 2 i) 1)) (. poly (- (* 2 j) 1)))
                dv (- (. poly (* 2 i)) (. poly (* 2 j)))
                dw (- (. ws i) (. ws j))]
            (set d (max d (sqrt (+ (* du du) (* dv dv) (* dw dw))))))))
      ;; Triangles that only touch along an edge leave a polygon of no width (its
      ;; projected area over its diameter): a segment in common, not an overlap.
      (if (or (= d 0) (<= (/ (* 0.5 (abs area)) d) (* on-plane scale))) 0 d))))

;; Where the two cuts of a crossing pair must agree (a share of the triangles'
;; size): their points carry rounding of some 1e-16 of it over the sine of the
;; planes' angle, so 1e-8 holds down to angles of some 1e-7.
(local agree 1e-8)

;; Planes whose normals' angle has a sine under this are taken as one (see
;; pair-overlap).
(local parallel 1e-6)

(fn point-at [pts lx ly lz ll s]
  "The point of the cut `pts` (one or two points) whose parameter along the unit
direction l/ll is `s`."
  (let [x0 (. pts 1) y0 (. pts 2) z0 (. pts 3)
        s0 (/ (dot lx ly lz x0 y0 z0) ll)]
    (if (< (length pts) 6) (values x0 y0 z0)
        (let [x1 (. pts 4) y1 (. pts 5) z1 (. pts 6)
              s1 (/ (dot lx ly lz x1 y1 z1) ll)
              t (if (= s1 s0) 0 (/ (- s s0) (- s1 s0)))]
          (values (+ x0 (* t (- x1 x0))) (+ y0 (* t (- y1 y0))) (+ z0 (* t (- z1 z0))))))))

(fn gap [cp cq lx ly lz ll s]
  "How far apart the cuts `cp` and `cq` are at parameter `s` along the line."
  (let [(ax ay az) (point-at cp lx ly lz ll s)
        (bx by bz) (point-at cq lx ly lz ll s)]
    (sqrt (+ (* (- ax bx) (- ax bx)) (* (- ay by) (- ay by)) (* (- az bz) (- az bz))))))

(fn snap [d tol]
  ;; Zero for a distance within rounding of a plane.
  (if (< (abs d) tol) 0 d))

(fn plane-distance [nx ny nz ln ox oy oz x y z]
  ;; The signed distance of x y z from the plane through o of normal n (length ln).
  (/ (dot nx ny nz (- x ox) (- y oy) (- z oz)) ln))

(fn one-side? [a b c]
  ;; Whether a triangle whose corners are a b c from a plane meets it in a point at
  ;; most: all on one side, save one corner on the plane (a pair sharing a vertex).
  (let [pos (+ (if (> a 0) 1 0) (if (> b 0) 1 0) (if (> c 0) 1 0))
        neg (+ (if (< a 0) 1 0) (if (< b 0) 1 0) (if (< c 0) 1 0))]
    (or (and (= neg 0) (>= pos 2)) (and (= pos 0) (>= neg 2)))))

(fn cut-range [pts lx ly lz ll]
  ;; The parameters along the unit direction l/ll that the cut `pts` spans.
  (var (lo hi) (values math.huge (- math.huge)))
  (for [b 0 (- (length pts) 1) 3]
    (let [s (/ (dot lx ly lz (. pts (+ b 1)) (. pts (+ b 2)) (. pts (+ b 3))) ll)]
      (set (lo hi) (values (min lo s) (max hi s)))))
  (values lo hi))

(fn shared-corner [p q]
  ;; The corners (1-3 each) of p and q at the same point, when exactly one is;
  ;; else nil.
  (var (found fi fj) (values 0 nil nil))
  (for [i 0 2]
    (for [j 0 2]
      (when (and (= (. p (+ 1 (* 3 i))) (. q (+ 1 (* 3 j))))
                 (= (. p (+ 2 (* 3 i))) (. q (+ 2 (* 3 j))))
                 (= (. p (+ 3 (* 3 i))) (. q (+ 3 (* 3 j)))))
        (set (found fi fj) (values (+ found 1) (+ i 1) (+ j 1))))))
  (when (= found 1) (values fi fj)))

(fn cross2 [ax ay bx by] (- (* ax by) (* ay bx)))

(fn inside-wedge? [dx dy ax ay bx by]
  ;; Whether direction d is strictly between a and b (counter-clockwise a to b).
  (and (> (cross2 ax ay dx dy) 0) (> (cross2 dx dy bx by) 0)))

(fn wedge [t k iu iv]
  ;; Triangle t's two edges from corner k, projected on coordinates iu iv, in
  ;; counter-clockwise order, and their bisector; nil when degenerate.
  (let [k1 (+ 1 (% k 3)) k2 (+ 1 (% (+ k 1) 3))
        ox (. t (+ iu (* 3 (- k 1)))) oy (. t (+ iv (* 3 (- k 1))))
        ax (- (. t (+ iu (* 3 (- k1 1)))) ox) ay (- (. t (+ iv (* 3 (- k1 1)))) oy)
        bx (- (. t (+ iu (* 3 (- k2 1)))) ox) by (- (. t (+ iv (* 3 (- k2 1)))) oy)
        c (cross2 ax ay bx by)
        la (sqrt (+ (* ax ax) (* ay ay))) lb (sqrt (+ (* bx bx) (* by by)))]
    (if (or (= c 0) (= la 0) (= lb 0)) nil
        (< c 0) (values bx by ax ay (+ (/ ax la) (/ bx lb)) (+ (/ ay la) (/ by lb)))
        (values ax ay bx by (+ (/ ax la) (/ bx lb)) (+ (/ ay la) (/ by lb))))))

(fn wedges-apart? [p q nx ny nz]
  "Whether coplanar triangles p and q (normal n) sharing exactly one corner meet
only there: near that corner each is its wedge, and two pointed wedges share
interior exactly when a side or the bisector of one is strictly inside the other.
False when they share no corner or more than one (the full test decides). A fast
answer for the commonest pair of a flat face, a vertex's neighbours."
  (case (shared-corner p q)
    (i j)
    (let [ax (abs nx) ay (abs ny) az (abs nz)
          (iu iv) (if (and (>= ax ay) (>= ax az)) (values 2 3)
                      (>= ay az) (values 3 1)
                      (values 1 2))
          (a1x a1y a2x a2y amx amy) (wedge p i iu iv)
          (b1x b1y b2x b2y bmx bmy) (wedge q j iu iv)]
      (and a1x b1x
           (not (or (inside-wedge? b1x b1y a1x a1y a2x a2y)
                    (inside-wedge? b2x b2y a1x a1y a2x a2y)
                    (inside-wedge? bmx bmy a1x a1y a2x a2y)
                    (inside-wedge? a1x a1y b1x b1y b2x b2y)
                    (inside-wedge? a2x a2y b1x b1y b2x b2y)
                    (inside-wedge? amx amy b1x b1y b2x b2y)))))
    _ false))

(fn pair-overlap [p q]
  "The length of what triangles `p` and `q` (each [x y z x y z x y z]) have in
common: 0 when apart or touching at a point, the length of their common segment
when they cross or touch along one, the diameter of their common area when
coplanar and overlapping. Second value: :crossing, :coplanar or nil."
  (let [[p1x p1y p1z p2x p2y p2z p3x p3y p3z] p
        [q1x q1y q1z q2x q2y q2z q3x q3y q3z] q
        (ux uy uz) (sub p2x p2y p2z p1x p1y p1z)
        (vx vy vz) (sub p3x p3y p3z p1x p1y p1z)
        (nx ny nz) (cross ux uy uz vx vy vz)
        (sx sy sz) (sub q2x q2y q2z q1x q1y q1z)
        (tx ty tz) (sub q3x q3y q3z q1x q1y q1z)
        (mx my mz) (cross sx sy sz tx ty tz)
        ;; The scale of both triangles: the longest edge vector's coordinate.
        scale (max (abs ux) (abs uy) (abs uz) (abs vx) (abs vy) (abs vz)
                   (abs sx) (abs sy) (abs sz) (abs tx) (abs ty) (abs tz))
        ln (sqrt (dot nx ny nz nx ny nz))
        lm (sqrt (dot mx my mz mx my mz))]
    (if (or (= ln 0) (= lm 0) (= scale 0))
        ;; A degenerate triangle (a segment or a point) is another kind of fault
        ;; (check.topology counts them); it crosses nothing here.
        (values 0 nil)
        (let [tol (* on-plane scale)
              ;; Distances of q's vertices from p's plane, and p's from q's (in
              ;; locals, and no closure: most pairs end at the next test, and this
              ;; runs for every pair whose boxes overlap).
              dq1 (snap (plane-distance nx ny nz ln p1x p1y p1z q1x q1y q1z) tol)
              dq2 (snap (plane-distance nx ny nz ln p1x p1y p1z q2x q2y q2z) tol)
              dq3 (snap (plane-distance nx ny nz ln p1x p1y p1z q3x q3y q3z) tol)
              dp1 (snap (plane-distance mx my mz lm q1x q1y q1z p1x p1y p1z) tol)
              dp2 (snap (plane-distance mx my mz lm q1x q1y q1z p2x p2y p2z) tol)
              dp3 (snap (plane-distance mx my mz lm q1x q1y q1z p3x p3y p3z) tol)]
          (if (or (one-side? dq1 dq2 dq3) (one-side? dp1 dp2 dp3))
              (values 0 nil)
              ;; In one plane, or as good as: planes within a millionth of a
              ;; radian meet along a line that rounding moves anywhere, and the
              ;; cuts along it gave a fold of half a cell between two triangles
              ;; of one flat fan on opposite sides of their vertex (platonic-shelf
              ;; at 128 cells). Triangles that cross at so small an angle overlap
              ;; seen along the normal, which the coplanar test measures.
              (or (and (= 0 dq1) (= 0 dq2) (= 0 dq3))
                  (let [(cx cy cz) (cross nx ny nz mx my mz)]
                    (< (sqrt (dot cx cy cz cx cy cz)) (* parallel ln lm))))
              (if (wedges-apart? p q nx ny nz)
                  (values 0 nil)
                  (let [d (coplanar-overlap p q nx ny nz scale)]
                    (values d (when (> d 0) :coplanar))))
              ;; Each triangle's cut by the other's plane lies on the line where
              ;; the planes meet, of direction n x m: the overlap of the two cuts
              ;; along it is what they share.
              (let [cp (plane-cut p [dp1 dp2 dp3])
                    cq (plane-cut q [dq1 dq2 dq3])
                    (lx ly lz) (cross nx ny nz mx my mz)
                    ll (sqrt (dot lx ly lz lx ly lz))]
                (if (or (= 0 (length cp)) (= 0 (length cq)) (= ll 0))
                    (values 0 nil)
                    (let [(a0 a1) (cut-range cp lx ly lz ll)
                          (b0 b1) (cut-range cq lx ly lz ll)
                          s0 (max a0 b0) s1 (min a1 b1)
                          d (- s1 s0)]
                      (if (<= d 0) (values 0 nil)
                          ;; Both cuts lie on the planes' line only as well as that
                          ;; line is defined: for nearly parallel planes it is not,
                          ;; and the cuts, far apart, may still overlap along it.
                          ;; Where the overlap's ends are not one point on both
                          ;; cuts, the triangles are as good as coplanar.
                          (and (< (gap cp cq lx ly lz ll s0) (* agree scale))
                               (< (gap cp cq lx ly lz ll s1) (* agree scale)))
                          (values d :crossing)
                          (let [c (coplanar-overlap p q nx ny nz scale)]
                            (values c (when (> c 0) :coplanar))))))))))))

(fn triangle-points [positions tris t out]
  ;; Triangle t's (0-based) corners as [x y z x y z x y z], into `out` (reused
  ;; from pair to pair: pair-overlap keeps neither).
  (for [c 1 3]
    (let [b (* 3 (- (. tris (+ (* 3 t) c)) 1))
          o (* 3 (- c 1))]
      (for [q 1 3] (tset out (+ o q) (. positions (+ b q))))))
  out)

(fn shared-vertices [tris s t]
  (var n 0)
  (for [a 1 3]
    (for [b 1 3]
      (when (= (. tris (+ (* 3 s) a)) (. tris (+ (* 3 t) b)))
        (set n (+ n 1)))))
  n)

(fn self-intersections [m ?options]
  "The pairs of triangles of mesh `m` that cross: {:pairs (pairs sharing no vertex
whose common part, see pair-overlap, is longer than :min-length) :coplanar (those
of them that overlap in a plane) :longest (the longest common part of those) :at
[x y z] (a point of that longest one's triangles) :folds (pairs sharing one vertex
that meet along more than that vertex: a fold through the vertex) :fold-list [[s t
length] ...] (the first :max-list folds, as :list) :tested (pairs
whose boxes overlap, tested exactly) :list [[s t length] ...] (the first
:max-list pairs, 0-based triangle indices)}. Pairs sharing an edge meet along it
and are not tested. Options: :min-length (default 1e-9 of the mesh's size; pass
e.g. 1e-6 cells), :max-list (default 100), :only (a table whose keys are the
1-based triangles to test, each against every triangle; default all), :folds?
(false: pairs sharing a vertex are not tested, and :folds stays 0), :tick (called
every tick-every triangles: a caller's progress, which may raise to stop)."
  (let [options (or ?options {})
        positions m.positions
        tris m.triangles
        nt (/ (length tris) 3)
        max-list (or options.max-list 100)
        ;; Each triangle's box, and the mean of their largest sides: the grid's
        ;; cell (a triangle then spans a few cells at most).
        box []
        result {:pairs 0 :coplanar 0 :folds 0 :tested 0 :longest 0 :at nil :list []
                :fold-list []}]
    (var (glo-x glo-y glo-z ghi-x ghi-y ghi-z) (values math.huge math.huge math.huge
                                                       (- math.huge) (- math.huge) (- math.huge)))
    (var side-sum 0)
    ;; Each triangle's box as six numbers, read from the positions in place (no
    ;; table per triangle: this runs over every triangle of a mesh).
    (for [t 0 (- nt 1)]
      (let [a (* 3 (- (. tris (+ (* 3 t) 1)) 1))
            b (* 3 (- (. tris (+ (* 3 t) 2)) 1))
            c (* 3 (- (. tris (+ (* 3 t) 3)) 1))
            x1 (. positions (+ a 1)) y1 (. positions (+ a 2)) z1 (. positions (+ a 3))
            x2 (. positions (+ b 1)) y2 (. positions (+ b 2)) z2 (. positions (+ b 3))
            x3 (. positions (+ c 1)) y3 (. positions (+ c 2)) z3 (. positions (+ c 3))
            lx (min x1 x2 x3) ly (min y1 y2 y3) lz (min z1 z2 z3)
            hx (max x1 x2 x3) hy (max y1 y2 y3) hz (max z1 z2 z3)
            o (* 6 t)]
        (tset box (+ o 1) lx) (tset box (+ o 2) ly) (tset box (+ o 3) lz)
        (tset box (+ o 4) hx) (tset box (+ o 5) hy) (tset box (+ o 6) hz)
        (set side-sum (+ side-sum (max (- hx lx) (- hy ly) (- hz lz))))
        (set (glo-x glo-y glo-z) (values (min glo-x lx) (min glo-y ly) (min glo-z lz)))
        (set (ghi-x ghi-y ghi-z) (values (max ghi-x hx) (max ghi-y hy) (max ghi-z hz)))))
    (when (> nt 1)
      (let [size (max (- ghi-x glo-x) (- ghi-y glo-y) (- ghi-z glo-z))
            min-length (or options.min-length (* 1e-9 size))
            ;; At least 1/1000 of the mesh's size, so a mesh of slivers does not
            ;; make more cells than triangles.
            cell (max (* 2 (/ side-sum nt)) (* 1e-3 size) 1e-300)
            gx (+ 1 (floor (/ (- ghi-x glo-x) cell)))
            gy (+ 1 (floor (/ (- ghi-y glo-y) cell)))
            at (fn [v lo] (floor (/ (- v lo) cell)))
            key (fn [i j k] (+ i (* gx (+ j (* gy k)))))
            buckets {}
            only options.only
            listed? (fn [t] (or (not only) (. only t)))
            folds? (not= false options.folds?)
            p-points [] r-points []
            test! (fn [s t]
                    (let [shared (shared-vertices tris (- s 1) (- t 1))]
                      (when (< shared (if folds? 2 1))
                        (set result.tested (+ result.tested 1))
                        (let [p (triangle-points positions tris (- s 1) p-points)
                              r (triangle-points positions tris (- t 1) r-points)
                              (len kind) (pair-overlap p r)]
                          (when (> len min-length)
                            (if (= shared 1)
                                (do (set result.folds (+ result.folds 1))
                                    (when (< (length result.fold-list) max-list)
                                      (table.insert result.fold-list [(- s 1) (- t 1) len])))
                                (do
                                  (set result.pairs (+ result.pairs 1))
                                  (when (= kind :coplanar)
                                    (set result.coplanar (+ result.coplanar 1)))
                                  (when (< (length result.list) max-list)
                                    (table.insert result.list [(- s 1) (- t 1) len]))
                                  (when (> len result.longest)
                                    (set result.longest len)
                                    (set result.at [(. p 1) (. p 2) (. p 3)])))))))))]
        ;; The grid holds the triangles to test (all, or those of :only); every
        ;; triangle then meets those in the cells its box covers.
        (for [t 1 nt]
          (when (listed? t)
            (let [o (* 6 (- t 1))]
              (for [k (at (. box (+ o 3)) glo-z) (at (. box (+ o 6)) glo-z)]
                (for [j (at (. box (+ o 2)) glo-y) (at (. box (+ o 5)) glo-y)]
                  (for [i (at (. box (+ o 1)) glo-x) (at (. box (+ o 4)) glo-x)]
                    (let [q (key i j k)
                          list (. buckets q)]
                      (if list (table.insert list t) (tset buckets q [t])))))))))
        (for [t 1 nt]
          (when (and options.tick (= 0 (% t tick-every))) (options.tick))
          (let [ot (* 6 (- t 1))
                tlx (. box (+ ot 1)) tly (. box (+ ot 2)) tlz (. box (+ ot 3))
                thx (. box (+ ot 4)) thy (. box (+ ot 5)) thz (. box (+ ot 6))
                t-listed? (listed? t)]
            (for [k (at tlz glo-z) (at thz glo-z)]
              (for [j (at tly glo-y) (at thy glo-y)]
                (for [i (at tlx glo-x) (at thx glo-x)]
                  (let [q (key i j k)]
                    (case (. buckets q)
                      list
                      (each [_ s (ipairs list)]
                        (let [os (* 6 (- s 1))
                              lx (max (. box (+ os 1)) tlx) ly (max (. box (+ os 2)) tly)
                              lz (max (. box (+ os 3)) tlz)]
                          ;; A pair of listed triangles is met from both sides:
                          ;; taken from the later one's. Boxes that overlap, tested
                          ;; only in the cell holding the low corner of their
                          ;; overlap, so each pair once.
                          (when (and (if t-listed? (< s t) (not= s t))
                                     (<= lx (min (. box (+ os 4)) thx))
                                     (<= ly (min (. box (+ os 5)) thy))
                                     (<= lz (min (. box (+ os 6)) thz))
                                     (= q (key (at lx glo-x) (at ly glo-y) (at lz glo-z))))
                            (test! (min s t) (max s t))))))))))))))
    result))

(fn fan-ends [tris t v]
  ;; Triangle t's (0-based) other two corners than v, in its winding order.
  (let [c1 (. tris (+ (* 3 t) 1)) c2 (. tris (+ (* 3 t) 2)) c3 (. tris (+ (* 3 t) 3))]
    (if (= c1 v) (values c2 c3) (= c2 v) (values c3 c1) (values c1 c2))))

(fn umbrella? [positions tris normals around first last v marks fan]
  "Whether the triangles around vertex v (0-based indices around[first..last]) lie
over a disc once, like an umbrella's panels: their far edges close around v (each
triangle's second end is another's first), seen along their summed normal m
(`normals`: each triangle's, 3 numbers from index 1) each turns counter-clockwise
about v, and a direction r inside the first lies inside exactly one of them (a fan
closed in several cycles, each turning, covers the disc once per cycle). Then no
two of them overlap beyond v (their shadows tile the disc, for any m they all turn
about), and the pairs need no test. Seen along m is by the sign of a product with
m: no projection. `marks` has a 0 for every vertex, and is left so; `fan` is
scratch (per triangle its two ends)."
  (let [b (* 3 (- v 1))
        vx (. positions (+ b 1)) vy (. positions (+ b 2)) vz (. positions (+ b 3))]
    (var (mx my mz ok?) (values 0 0 0 true))
    ;; Each first end counted, once at most.
    (for [q first last]
      (let [t (. around q)
            (ia ib) (fan-ends tris t v)
            f (* 2 (- q first))
            n (* 3 t)]
        (tset fan (+ f 1) ia) (tset fan (+ f 2) ib)
        (when (< 0 (. marks ia)) (set ok? false))
        (tset marks ia 1)
        (set (mx my mz) (values (+ mx (. normals (+ n 1))) (+ my (. normals (+ n 2)))
                                (+ mz (. normals (+ n 3)))))))
    ;; r strictly inside the first wedge (its angle is under half a turn); a
    ;; wedge [a, b) holds r where a x r . m >= 0 and r x b . m > 0, that is
    ;; a . w >= 0 and b . w < 0 with w = r x m.
    (let [p1 (* 3 (- (. fan 1) 1)) p2 (* 3 (- (. fan 2) 1))
          rx (+ (- (. positions (+ p1 1)) vx) (- (. positions (+ p2 1)) vx))
          ry (+ (- (. positions (+ p1 2)) vy) (- (. positions (+ p2 2)) vy))
          rz (+ (- (. positions (+ p1 3)) vz) (- (. positions (+ p2 3)) vz))
          (wx wy wz) (cross rx ry rz mx my mz)
          n (- last first)]
      (var covering 0)
      (for [q 0 n]
        (let [t (. around (+ first q))
              ia (. fan (+ (* 2 q) 1)) ib (. fan (+ (* 2 q) 2))
              pa (* 3 (- ia 1)) pb (* 3 (- ib 1)) nt (* 3 t)]
          (tset marks ib (- (. marks ib) 1))
          (when (<= (dot (. normals (+ nt 1)) (. normals (+ nt 2)) (. normals (+ nt 3)) mx my mz) 0)
            (set ok? false))
          (when (and (>= (dot (- (. positions (+ pa 1)) vx) (- (. positions (+ pa 2)) vy)
                              (- (. positions (+ pa 3)) vz) wx wy wz)
                         0)
                     (< (dot (- (. positions (+ pb 1)) vx) (- (. positions (+ pb 2)) vy)
                             (- (. positions (+ pb 3)) vz) wx wy wz)
                        0))
            (set covering (+ covering 1)))))
      ;; Every end met as often as a first end as a second; the marks back to 0.
      (for [q 1 (* 2 (+ n 1))]
        (when (not= 0 (. marks (. fan q))) (set ok? false)))
      (for [q 1 (* 2 (+ n 1))]
        (tset marks (. fan q) 0))
      (and ok? (= covering 1)))))

(fn folds [m ?options]
  "The folds of mesh `m`: pairs of triangles sharing exactly one vertex that meet
along more than it (see pair-overlap), found through each vertex's triangles (no
broad phase: a fold's triangles are neighbours). Returns a list [[s t length] ...]
(0-based triangle indices). Options: :min-length (as self-intersections'), :only (a
table whose keys are the 1-based vertices to look around; default all), :tick (as
self-intersections')."
  (let [options (or ?options {})
        positions m.positions
        tris m.triangles
        nt (/ (length tris) 3)
        nv (/ (length positions) 3)
        only options.only
        min-length (or options.min-length 0)
        ;; Each vertex's triangles, compressed: start[v] .. start[v + 1] - 1 of `around`.
        start (int-array (+ nv 1))
        around (int-array (* 3 nt))
        p-points [] r-points [] fan []
        marks (int-array nv)
        ;; Each triangle's normal (twice its area long), 3 numbers from 3t + 1.
        normals (float-array (* 3 nt))
        out []]
    (for [t 0 (- nt 1)]
      (let [a (* 3 (- (. tris (+ (* 3 t) 1)) 1))
            b (* 3 (- (. tris (+ (* 3 t) 2)) 1))
            c (* 3 (- (. tris (+ (* 3 t) 3)) 1))
            ax (. positions (+ a 1)) ay (. positions (+ a 2)) az (. positions (+ a 3))
            (x y z) (cross (- (. positions (+ b 1)) ax) (- (. positions (+ b 2)) ay)
                           (- (. positions (+ b 3)) az) (- (. positions (+ c 1)) ax)
                           (- (. positions (+ c 2)) ay) (- (. positions (+ c 3)) az))]
        (tset normals (+ (* 3 t) 1) x) (tset normals (+ (* 3 t) 2) y)
        (tset normals (+ (* 3 t) 3) z)))
    (for [q 1 (* 3 nt)]
      (let [v (. tris q)] (tset start v (+ 1 (. start v)))))
    (var sum 1)
    (for [v 1 (+ nv 1)]
      (let [c (. start v)] (tset start v sum) (set sum (+ sum c))))
    (let [fill (int-array nv)]
      (for [v 1 nv] (tset fill v (. start v)))
      (for [t 0 (- nt 1)]
        (for [c 1 3]
          (let [v (. tris (+ (* 3 t) c))]
            (tset around (. fill v) t)
            (tset fill v (+ 1 (. fill v)))))))
    (for [v 1 nv]
      (when (and options.tick (= 0 (% v tick-every))) (options.tick))
      ;; (A vertex no triangle uses has no fan, and no fold.)
      (when (and (or (not only) (. only v))
                 (< (. start v) (. start (+ v 1)))
                 (not (umbrella? positions tris normals around (. start v)
                                 (- (. start (+ v 1)) 1) v marks fan)))
        (for [a (. start v) (- (. start (+ v 1)) 1)]
          (for [b (+ a 1) (- (. start (+ v 1)) 1)]
            (let [s (. around a) t (. around b)]
              (when (= 1 (shared-vertices tris s t))
                (let [len (pair-overlap (triangle-points positions tris s p-points)
                                        (triangle-points positions tris t r-points))]
                  (when (> len min-length)
                    (table.insert out [(min s t) (max s t) len])))))))))
    out))

{: self-intersections : pair-overlap : folds}

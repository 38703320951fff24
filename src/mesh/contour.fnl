;; Dual contouring of a signed distance field into a closed triangle mesh (--mesh).
;; The field is sampled at the corners of a grid of cubic cells, only in blocks its
;; own values cannot prove far from the surface (an octree of blocks, skipped where
;; |d| at a block's centre exceeds its half-diagonal), so the work follows the surface
;; area. Every grid edge whose ends differ in sign gets a crossing point (regula falsi
;; on the field) and the field's gradient there; every cell gets one vertex per patch
;; of surface in it, placed where the tangent planes of its crossings meet (a QEF, kept
;; inside the cell), which keeps sharp edges and corners; every crossing edge gives a
;; quad of the four cells around it.
;;
;; Patches: a cell's crossing edges are joined into patches along the faces of the
;; cell, a face with two crossings joining them and a face with four (ambiguous)
;; joining them as the face's bilinear interpolant does (the asymptotic decider: it
;; reads only the face's four corner values, so both cells of a face decide alike).
;; With one vertex per patch instead of one per cell, two sheets through one cell (a
;; thin wall, two objects touching) get a vertex each and the mesh stays 2-manifold.
;; With the field cut by a box inside the grid the grid's boundary is all outside, so
;; every crossing edge has its four cells and the mesh is closed.
;;
;; Pure: runs under plain LuaJIT. The field is a table of batch functions (see mesh),
;; so the same mesher runs on the CPU evaluator and on the GPU.

;; `pairs` under another name: a loop over `pairs` by that name is LuaJIT's ITERN,
;; which Debian 12's LuaJIT ends early once despecialised (see src/util/wire.fnl).
(local each-pair pairs)

(local intersect (require :src.mesh.intersect))
(local fork (require :src.util.fork))
(local bit (require :bit))
(local {: table-new : int-array : byte-array : float-array} (require :src.util.arrays))

(local sqrt math.sqrt)
(local floor math.floor)
(local abs math.abs)
(local min math.min)
(local max math.max)

;; Cells per side of a leaf block (the blocks whose corners are sampled), and of the
;; largest blocks the octree starts from.
(local leaf 4)
(local top 32)
;; Points per call of the field's batch functions.
(local batch-size 32768)
;; A vertex farther than this (in cells) from the surface is moved onto it. The QEF
;; puts the vertex of a sharp edge or corner on the surface, so this leaves them be;
;; what it moves are vertices clamped to their cell and those of features thinner
;; than a cell, whose tangent planes meet far away.
(local off-surface 0.25)
;; The work of the steps that evaluate nothing (finding the cells, their patches,
;; vertices and quads), counted in field evaluations per crossing for the time-left
;; estimate: machined-part at 256 cells took 1.2 s for them and 79k crossings, about
;; 15 microseconds each, while its evaluations took 0.8 microseconds each (organic's
;; three times that): about 10 evaluations' worth. The caller may add its own work
;; per vertex (:after-work of the grid: the export's colours).
(local geometry-work 10)
;; Regula falsi steps refining each crossing after the linear guess from the corners.
(local refine-steps 4)
;; The QEF's pull toward the mean of the crossings, per crossing (normals are unit,
;; so the planes' matrix has eigenvalues up to the crossing count): where the normals
;; are nearly parallel (a smooth surface) it keeps the vertex near the crossings
;; instead of far along the surface, and at a corner of three orthogonal faces
;; (eigenvalues near 1/3 per crossing) it moves the vertex by about 1/300 of its
;; distance to the mean, under 1% of a cell.
(local pull 0.001)

;;; Cells: corners c = x + 2y + 4z; edges 0-3 along x (at y + 2z), 4-7 along y (at
;;; x + 2z), 8-11 along z (at x + 2y).

(fn corner-bits [c] (values (% c 2) (% (floor (/ c 2)) 2) (floor (/ c 4))))

(fn edge-between [a b]
  "The local edge joining corners a and b (which differ along one axis)."
  (let [(ax ay az) (corner-bits a)
        (bx by bz) (corner-bits b)]
    (if (not= ax bx) (+ ay (* 2 az))
        (not= ay by) (+ 4 ax (* 2 az))
        (+ 8 ax (* 2 ay)))))

;; Each edge's two corners, low end first.
(local edge-corners
  (fcollect [e 0 11]
    (let [axis (floor (/ e 4)) r (% e 4) p (% r 2) q (floor (/ r 2))
          ;; The two other coordinates, in cyclic-free order: x: (y z), y: (x z), z: (x y).
          lo (case axis 0 (+ (* 2 p) (* 4 q)) 1 (+ p (* 4 q)) _ (+ p (* 2 q)))]
      [lo (+ lo (case axis 0 1 1 2 _ 4))])))

;; Each face's four corners in cyclic order and its four edges (edge k joins corner k
;; to corner k+1).
(local faces
  (let [out []]
    (for [axis 0 2]
      (for [side 0 1]
        (let [u (% (+ axis 1) 3) v (% (+ axis 2) 3)
              at (fn [a b] (+ (* side (^ 2 axis)) (* a (^ 2 u)) (* b (^ 2 v))))
              cs [(at 0 0) (at 1 0) (at 1 1) (at 0 1)]]
          (table.insert out {:corners cs
                             :edges (fcollect [k 1 4]
                                      (edge-between (. cs k) (. cs (+ 1 (% k 4)))))}))))
    out))

;; Each edge's corners, as two flat lists (the inner loops read no pair).
(local edge-low (icollect [_ [a _] (ipairs edge-corners)] a))
(local edge-high (icollect [_ [_ b] (ipairs edge-corners)] b))
;; Each edge's low corner's offset in the cell, and its axis.
(local edge-dx (icollect [_ [a _] (ipairs edge-corners)] (% a 2)))
(local edge-dy (icollect [_ [a _] (ipairs edge-corners)] (% (floor (/ a 2)) 2)))
(local edge-dz (icollect [_ [a _] (ipairs edge-corners)] (floor (/ a 4))))
(local edge-axis (fcollect [e 0 11] (floor (/ e 4))))

;; Where each local edge's cell stands in the quad of its crossing (see
;; make-triangles): the slot, 1-4, of the four cells around the edge, counter-
;; clockwise about its axis. Along x and z, local edge r = u + 2v of the cell's
;; offset (-u, -v) from the edge; along y, r = v + 2u.
(local edge-slot [3 4 2 1  3 2 4 1  3 4 2 1])

;;; Union-find over a cell's twelve edges.

(fn find [parent e]
  (var r e)
  (while (not= (. parent r) r) (set r (. parent r)))
  r)

(fn join! [parent a b]
  (let [ra (find parent a) rb (find parent b)]
    (when (not= ra rb) (tset parent ra rb))))

;; The faces of most cells: none (shared, never written).
(local no-faces [])

;; The patches of the cells without an ambiguous face, by their corners' signs
;; (bit c set where corner c is inside): there the signs alone decide, and most
;; cells are so (on a torus at 128 cells, every one).
(local plain-patches {})

(fn patches [v ?flipped]
  "The patches of a cell with corner values `v` (1-based by corner c + 1; inside is
below 0): a table from each crossing edge (0-11) to its patch's representative, and
a list of the cell's ambiguous faces (1-6) whose two segments belong to one patch.
`?flipped` (a table of faces 1-6) reverses the asymptotic decider on those faces.
The tables returned may be shared between cells: not to be changed."
  (let [mask (+ (if (< (. v 1) 0) 1 0) (if (< (. v 2) 0) 2 0) (if (< (. v 3) 0) 4 0)
                (if (< (. v 4) 0) 8 0) (if (< (. v 5) 0) 16 0) (if (< (. v 6) 0) 32 0)
                (if (< (. v 7) 0) 64 0) (if (< (. v 8) 0) 128 0))
        known (and (not ?flipped) (. plain-patches mask))]
    (if known
        (values known no-faces)
        (let [parent {}]
          (var joined nil)
          (var ambiguous? false)
          (for [e 0 11]
            (let [[a b] (. edge-corners (+ e 1))]
              (when (not= (< (. v (+ a 1)) 0) (< (. v (+ b 1)) 0))
                (tset parent e e))))
          (each [fi f (ipairs faces)]
            (let [[c0 c1 c2 c3] f.corners
                  [e01 e12 e23 e30] f.edges
                  n (+ (if (. parent e01) 1 0) (if (. parent e12) 1 0)
                       (if (. parent e23) 1 0) (if (. parent e30) 1 0))]
              (if (= n 2)
                  (let [ends (icollect [_ e (ipairs f.edges)] (when (. parent e) e))]
                    (join! parent (. ends 1) (. ends 2)))
                  (= n 4)
                  ;; Ambiguous: corners 0 and 2 have one sign, 1 and 3 the other.
                  ;; They are joined across the face when the bilinear
                  ;; interpolant's saddle has their sign; then the face's two
                  ;; segments cut off corners 1 and 3.
                  (let [a (. v (+ c0 1)) b (. v (+ c1 1)) c (. v (+ c2 1)) d (. v (+ c3 1))
                        saddle (/ (- (* a c) (* b d)) (- (+ a c) b d))]
                    (set ambiguous? true)
                    (if (not= (= (< saddle 0) (< a 0)) (not= nil (and ?flipped (. ?flipped fi))))
                        (do (join! parent e01 e12) (join! parent e23 e30))
                        (do (join! parent e30 e01) (join! parent e12 e23)))))))
          ;; e01 and e23 are on different segments either way.
          (each [fi f (ipairs faces)]
            (let [[e01 e12 e23 e30] f.edges]
              (when (and (. parent e01) (. parent e12) (. parent e23) (. parent e30)
                         (= (find parent e01) (find parent e23)))
                (when (not joined) (set joined []))
                (table.insert joined fi))))
          (let [rep (collect [e _ (each-pair parent)] e (find parent e))]
            (when (not ambiguous?) (tset plain-patches mask rep))
            (values rep (or joined no-faces)))))))

;; Interpreted, not compiled: it runs once per mask of corners (256 at most), where
;; LuaJIT compiled some hundred traces of its short loops, which took longer than
;; running them.
(when jit (jit.off patches true))

;; Vertices keep this share of a cell inside their cell's walls, so that vertices of
;; neighbouring cells never meet: a surface lying on a cell wall (a box face on a grid
;; plane) would otherwise put vertices of both cells on the same point, and a file
;; without shared vertices (STL), welded by position, would pinch there. Two patches
;; of one cell whose vertices meet (boxes touching along an edge) are moved apart by
;; ten times this.
(local inset 1e-3)

(fn clamp-cell [v lo h]
  ;; (min and max, not branches: LuaJIT could not compile the side traces those
  ;; took in the vertex loop, "register coalescing too complex".)
  (let [a (+ lo (* inset h)) b (- (+ lo h) (* inset h))]
    (min b (max a v))))

;;; The QEF: the point nearest (in the least-squares sense) to the crossings' tangent
;;; planes, pulled slightly toward their mean.

(fn solve3 [a11 a12 a13 a22 a23 a33 b1 b2 b3]
  ;; Symmetric 3x3 system by Cramer's rule (the pull makes it positive definite).
  (let [c11 (- (* a22 a33) (* a23 a23))
        c12 (- (* a13 a23) (* a12 a33))
        c13 (- (* a12 a23) (* a13 a22))
        det (+ (* a11 c11) (* a12 c12) (* a13 c13))]
    (if (<= (abs det) 1e-300)
        (values 0 0 0)
        (let [c22 (- (* a11 a33) (* a13 a13))
              c23 (- (* a12 a13) (* a11 a23))
              c33 (- (* a11 a22) (* a12 a12))]
          (values (/ (+ (* c11 b1) (* c12 b2) (* c13 b3)) det)
                  (/ (+ (* c12 b1) (* c22 b2) (* c23 b3)) det)
                  (/ (+ (* c13 b1) (* c23 b2) (* c33 b3)) det))))))

(fn qef-vertex [ids first last px py pz nx ny nz lo-x lo-y lo-z h]
  "The vertex of the crossings ids[first..last] (indices into the crossing arrays;
0s skipped), clamped to the cell whose low corner is lo and side h, then the
crossings' mean."
  (var (cx cy cz m) (values 0 0 0 0))
  (for [q first last]
    (let [k (. ids q)]
      (when (not= k 0)
        (set (cx cy cz m) (values (+ cx (. px k)) (+ cy (. py k)) (+ cz (. pz k)) (+ m 1))))))
  (set (cx cy cz) (values (/ cx m) (/ cy m) (/ cz m)))
  (var (a11 a12 a13 a22 a23 a33 b1 b2 b3) (values 0 0 0 0 0 0 0 0 0))
  (for [q first last]
    (let [k (. ids q)]
      (when (not= k 0)
        (let [x (. nx k) y (. ny k) z (. nz k)
              r (+ (* x (- (. px k) cx)) (* y (- (. py k) cy)) (* z (- (. pz k) cz)))]
          (set (a11 a12 a13) (values (+ a11 (* x x)) (+ a12 (* x y)) (+ a13 (* x z))))
          (set (a22 a23 a33) (values (+ a22 (* y y)) (+ a23 (* y z)) (+ a33 (* z z))))
          (set (b1 b2 b3) (values (+ b1 (* x r)) (+ b2 (* y r)) (+ b3 (* z r))))))))
  (let [l (* pull m)
        (dx dy dz) (solve3 (+ a11 l) a12 a13 (+ a22 l) a23 (+ a33 l) b1 b2 b3)]
    (values (clamp-cell (+ cx dx) lo-x h) (clamp-cell (+ cy dy) lo-y h)
            (clamp-cell (+ cz dz) lo-z h)
            (clamp-cell cx lo-x h) (clamp-cell cy lo-y h) (clamp-cell cz lo-z h))))

;;; Evaluating the field in batches.

(fn box-distance [cut x y z]
  ;; Signed distance to the box {:lo :hi}: the cut that closes the mesh.
  (let [[lx ly lz] cut.lo [hx hy hz] cut.hi
        qx (- (abs (- x (* 0.5 (+ lx hx)))) (* 0.5 (- hx lx)))
        qy (- (abs (- y (* 0.5 (+ ly hy)))) (* 0.5 (- hy ly)))
        qz (- (abs (- z (* 0.5 (+ lz hz)))) (* 0.5 (- hz lz)))
        ox (max qx 0) oy (max qy 0) oz (max qz 0)]
    (+ (sqrt (+ (* ox ox) (* oy oy) (* oz oz))) (min (max qx qy qz) 0))))

;; The heap is kept within twice what was live at the last full collection (and at
;; least this many KB): LuaJIT's incremental collector, paced by allocation, fell
;; behind the evaluator's garbage while big arrays were live, and six identical runs
;; of platonic-shelf at 256 cells peaked anywhere from 470 MB to 1.6 GB (the Lua
;; heap alone 300 MB to 1.5 GB, in the corners step). A full collection when the
;; heap has doubled costs a few of them per mesh (the live heap grows by steps).
(local heap-floor (* 64 1024))

(fn bound-heap! [counts]
  "A full collection when the Lua heap has grown past twice the live heap at the
last one (counts.live-kb, KB). Not in a child of src/util/fork.fnl whose collector
is stopped (see fork.run-shares)."
  (when (and (> (collectgarbage :count) (* 2 (max heap-floor (or counts.live-kb 0))))
             (fork.collects?))
    (collectgarbage)
    (set counts.live-kb (collectgarbage :count))
    (set counts.collections (+ 1 (or counts.collections 0)))))

(fn evaluator [field cut counts progress h]
  "A function from a phase name and a flat list of points x y z ... to their
values (the field cut by the box `cut`, plus the field's :offset in cells of side
`h`), in
batches of batch-size points; each batch counts as work done (see mesh) and
`progress` hears of it."
  (let [[lx ly lz] cut.lo [hx hy hz] cut.hi
        ;; The cut box's centre and half sides, once (box-distance per point).
        mx (* 0.5 (+ lx hx)) my (* 0.5 (+ ly hy)) mz (* 0.5 (+ lz hz))
        sx (* 0.5 (- hx lx)) sy (* 0.5 (- hy ly)) sz (* 0.5 (- hz lz))
        offset (* (or field.offset 0) h)]
    (fn [phase flat ?n]
      (let [n (or ?n (/ (length flat) 3))
            out (table-new n)]
        (for [start 0 (- n 1) batch-size]
          (let [count (min batch-size (- n start))
                ;; A batch: the points after the first `start` of the list (no copy).
                ds (field.distances flat count start)]
            (for [k 1 count]
              (let [j (* 3 (+ start k -1))
                    d (. ds k)
                    qx (- (abs (- (. flat (+ j 1)) mx)) sx)
                    qy (- (abs (- (. flat (+ j 2)) my)) sy)
                    qz (- (abs (- (. flat (+ j 3)) mz)) sz)
                    ox (max qx 0) oy (max qy 0) oz (max qz 0)
                    b (+ (sqrt (+ (* ox ox) (* oy oy) (* oz oz))) (min (max qx qy qz) 0))]
                (tset out (+ start k) (+ (max d b) offset))))
            (set counts.points (+ counts.points count))
            (set counts.work (+ counts.work count))
            (bound-heap! counts)
            (progress phase counts.work counts.estimate counts.points)))
        out))))

;;; The mesher: one function per phase, in the order mesh calls them. What the
;;; phases share (the grid, the counts, the crossings, the cells, the vertices) is
;;; one state table, made by new-state and passed along; each phase reads what the
;;; ones before it left there and adds its own.

(fn new-state [field grid ?progress]
  "The state the phases of mesh share: the grid's corner, cell and size, the
gradient's step, the counts of work (see mesh), the evaluator and the CPU seconds
of each step."
  (let [progress (or ?progress (fn []))
        counts {:points 0 :work 0}
        [ox oy oz] grid.lo
        h grid.h
        [nx ny nz] grid.dims]
    {: progress : counts : field : grid
     :after (+ geometry-work (or grid.after-work 0))
     :evaluate (evaluator field grid.cut counts progress h)
     : ox : oy : oz : h : nx : ny : nz
     :step (* h (or field.step 1e-3))
     ;; Global keys of grid points: i + stride-x j + stride-y k.
     :stride-x (+ nx 1)
     :stride-y (* (+ nx 1) (+ ny 1))
     ;; CPU seconds of each step, for the figures (os.clock: a GPU field's waits
     ;; are not counted); mark! keeps the step under way and when it began.
     :times {}
     :marked-at (os.clock)
     :marked-step nil}))

(fn worked! [state phase units]
  "Count `units` of work not done by evaluating (see geometry-work), and tell
progress."
  (let [counts state.counts]
    (set counts.work (+ counts.work units))
    (state.progress phase counts.work counts.estimate counts.points)))

(fn mark! [state step]
  "End the step under way (its CPU seconds go to state.times) and begin `step`
(nil: none)."
  (let [now (os.clock)]
    (when state.marked-step
      (tset state.times state.marked-step (- now state.marked-at)))
    (set (state.marked-at state.marked-step) (values now step))))

(fn find-leaves! [state]
  "1. The octree of blocks: keep those whose centre's |d| does not prove them clear
of the surface; subdivide down to halves of leaves. Leaves state.leaves (their low
cells [i j k], each with a kept half), state.leaf-halves (per leaf, which of its
eight halves were kept: bit h = x + 2y + 4z of the half) and state.skipped (leaf
blocks' worth of volume skipped)."
  (let [{: evaluate : ox : oy : oz : h : nx : ny : nz} state]
    ;; The blocks of a level as one flat list of their low cells, i j k ... (no
    ;; table a block: some 26,000 halves on a torus at 128 cells).
    (var blocks [])
    (for [k 0 (- nz 1) top]
      (for [j 0 (- ny 1) top]
        (for [i 0 (- nx 1) top]
          (table.insert blocks i) (table.insert blocks j) (table.insert blocks k))))
    (var size top)
    (var halves nil)
    (var skipped 0)
    (while (not halves)
      (let [n (/ (length blocks) 3)
            flat (table-new (* 3 n))
            half (* 0.5 size h)
            radius (* 1.0001 (sqrt 3) half)]
        (for [q 1 (* 3 n) 3]
          (tset flat q (+ ox (* (. blocks q) h) half))
          (tset flat (+ q 1) (+ oy (* (. blocks (+ q 1)) h) half))
          (tset flat (+ q 2) (+ oz (* (. blocks (+ q 2)) h) half)))
        (let [ds (evaluate :blocks flat n)
              kept []]
          (for [b 1 n]
            (if (<= (abs (. ds b)) radius)
                (let [q (* 3 (- b 1))]
                  (table.insert kept (. blocks (+ q 1))) (table.insert kept (. blocks (+ q 2)))
                  (table.insert kept (. blocks (+ q 3))))
                (set skipped (+ skipped (/ (^ size 3) (^ leaf 3))))))
          (if (= size (/ leaf 2))
              (set halves kept)
              (let [s (/ size 2)]
                (set blocks [])
                (for [q 1 (length kept) 3]
                  (let [i (. kept q) j (. kept (+ q 1)) k (. kept (+ q 2))]
                    (for [c 0 7]
                      (let [(bx by bz) (corner-bits c)
                            a (+ i (* bx s)) b (+ j (* by s)) d (+ k (* bz s))]
                        (when (and (< a nx) (< b ny) (< d nz))
                          (table.insert blocks a) (table.insert blocks b)
                          (table.insert blocks d))))))
                (set size s))))))
    ;; The leaves are sampled whole (their corners); a half clear of the surface
    ;; (its centre farther than its half-diagonal: a fifth of a leaf's) is not:
    ;; the corners sampled, in the shell around the surface, are some 40% fewer
    ;; (measured below).
    (let [leaves [] leaf-halves [] at {}
          half (/ leaf 2)]
      (for [q 1 (length halves) 3]
        (let [i (. halves q) j (. halves (+ q 1)) k (. halves (+ q 2))
              li (- i (% i leaf)) lj (- j (% j leaf)) lk (- k (% k leaf))
              key (+ li (* (+ nx 1) (+ lj (* (+ ny 1) lk))))
              bit (^ 2 (+ (/ (- i li) half) (* 2 (/ (- j lj) half)) (* 4 (/ (- k lk) half))))]
          (var l (. at key))
          (when (not l)
            (table.insert leaves [li lj lk])
            (set l (length leaves))
            (tset at key l)
            (tset leaf-halves l 0))
          (tset leaf-halves l (+ (. leaf-halves l) bit))))
      (set (state.leaves state.leaf-halves state.skipped) (values leaves leaf-halves skipped)))))

(fn half-bit [q]
  ;; The lower (0) or upper (1) half of a leaf along one axis holding cell q.
  (if (< q (/ leaf 2)) 0 1))

;; Per corner (a b c) of a leaf, 0 to leaf, x fastest: the bits of the halves it is
;; a corner of (h = x + 2y + 4z; one on the middle plane belongs to the halves on
;; both sides). Per cell, 0 to leaf - 1: the bit of its half.
(local corner-halves
  (let [half (/ leaf 2) out []]
    (for [c 0 leaf]
      (for [b 0 leaf]
        (for [a 0 leaf]
          (var bits 0)
          (for [z (if (> c half) 1 0) (if (>= c half) 1 0)]
            (for [y (if (> b half) 1 0) (if (>= b half) 1 0)]
              (for [x (if (> a half) 1 0) (if (>= a half) 1 0)]
                (set bits (bit.bor bits (bit.lshift 1 (+ x (* 2 y) (* 4 z))))))))
          (table.insert out bits))))
    out))
(local cell-half
  (let [out []]
    (for [c 0 (- leaf 1)]
      (for [b 0 (- leaf 1)]
        (for [a 0 (- leaf 1)]
          (table.insert out (bit.lshift 1 (+ (half-bit a) (* 2 (half-bit b)) (* 4 (half-bit c))))))))
    out))

;; Per mask of kept halves, its leaf's corners to sample and cells to visit, as
;; flat lists [a b c ...] (made once a mask, not tested per corner).
(local mask-corners {})
(local mask-cells {})

(fn corners-of [halves]
  (or (. mask-corners halves)
      (let [out []]
        (var q 0)
        (for [c 0 leaf]
          (for [b 0 leaf]
            (for [a 0 leaf]
              (set q (+ q 1))
              (when (not= 0 (bit.band halves (. corner-halves q)))
                (table.insert out a) (table.insert out b) (table.insert out c)))))
        (tset mask-corners halves out)
        out)))

(fn cells-of [halves]
  (or (. mask-cells halves)
      (let [out []]
        (var q 0)
        (for [c 0 (- leaf 1)]
          (for [b 0 (- leaf 1)]
            (for [a 0 (- leaf 1)]
              (set q (+ q 1))
              (when (not= 0 (bit.band halves (. cell-half q)))
                (table.insert out a) (table.insert out b) (table.insert out c)))))
        (tset mask-cells halves out)
        out)))

;; The most grid points a dense index of them may have (4 bytes each: 256 MB); a
;; grid with more indexes its points in a hash table.
(local dense-points (* 64 1024 1024))

(local ffi (let [(ok? m) (pcall require :ffi)] (when ok? m)))

(fn grid-index [points]
  "An index from the keys of a grid's `points` (0 to points - 1) to numbers, all 0
at first: an array of 32-bit integers where LuaJIT's FFI is there and the grid is
not too large (no hashing: on a torus at 256 cells the hash table's lookups and
growth took a third of the sampling), else a table (nil at first)."
  (if (and ffi (<= points dense-points))
      (ffi.new "int32_t[?]" points)
      {}))

(fn sample-corners! [state]
  "2. The corners of the leaves' kept halves (see find-leaves!; clamped to the
grid): their values in state.corner-values, (leaf + 1)^3 slots a leaf, x fastest,
nil at the corners of no kept half. A grid point shared by leaves (their faces,
edges and corners) is evaluated once. Makes the first estimate of the work."
  (let [{: evaluate : counts : after : leaves : leaf-halves : ox : oy : oz : h : nx : ny : nz
         : stride-x : stride-y} state
        side (+ leaf 1)
        ;; Per leaf corner, the index of its grid point among the distinct ones.
        slots (table-new (* (length leaves) side side side))
        index (grid-index (* (+ nz 1) stride-y))
        ;; Per leaf corner, its grid point's index (find-cells! names edges by it).
        slot-points (int-array (* (length leaves) side side side))
        flat []]
    (var (n distinct) (values 0 0))
    (each [l [i j k] (ipairs leaves)]
      (let [corners (corners-of (. leaf-halves l))
            base (* (- l 1) side side side)]
        (for [q 1 (length corners) 3]
          (let [a (. corners q) b (. corners (+ q 1)) c (. corners (+ q 2))
                gi (min nx (+ i a)) gj (min ny (+ j b)) gk (min nz (+ k c))
                key (+ gi (* stride-x gj) (* stride-y gk))]
            (var at (. index key))
            (when (or (= at nil) (= at 0))
              (set distinct (+ distinct 1))
              (set at distinct)
              (tset index key at)
              (let [p (* 3 (- at 1))]
                (tset flat (+ p 1) (+ ox (* gi h)))
                (tset flat (+ p 2) (+ oy (* gj h)))
                (tset flat (+ p 3) (+ oz (* gk h)))))
            (set n (+ n 1))
            (tset slots (+ base 1 a (* side b) (* side side c)) at)
            (tset slot-points (+ base 1 a (* side b) (* side side c)) at)))))
    ;; The crossings and normals take about as many points again as the corners:
    ;; a leaf of 64 cells holds some 13 crossings where a surface crosses it (a
    ;; sphere at 32 cells), each taking 10 points (measured: 3990 crossings in 308
    ;; leaves); the estimate is made exact once the crossings are counted.
    (set counts.estimate (+ counts.work (* (+ 1 (/ n (max 1 distinct)) (/ after 10)) distinct)))
    (let [ds (evaluate :corners flat)
          ;; 1 where the value is inside (below 0): find-cells! adds them up.
          inside (byte-array (* (length leaves) side side side))]
      (for [q 1 (* (length leaves) side side side)]
        (case (. slots q)
          at (let [d (. ds at)]
               (tset slots q d)
               (when (< d 0) (tset inside q 1)))))
      (set (state.corner-values state.corner-inside state.slot-points state.point-count)
           (values slots inside slot-points distinct)))))

(fn mask-of [inside at side s2]
  ;; The cell's corners inside, as bits c = x + 2y + 4z, from its low corner's slot.
  (+ (. inside at) (* 2 (. inside (+ at 1))) (* 4 (. inside (+ at side)))
     (* 8 (. inside (+ at side 1))) (* 16 (. inside (+ at s2))) (* 32 (. inside (+ at s2 1)))
     (* 64 (. inside (+ at s2 side))) (* 128 (. inside (+ at s2 side 1)))))

;; Per mask of corners inside (+ 1), the local edges whose ends differ.
(local mask-edges
  (fcollect [mask 0 255]
    (fcollect [e 0 11]
      (let [bit (fn [c] (% (floor (/ mask (^ 2 c))) 2))]
        (when (not= (bit (. edge-low (+ e 1))) (bit (. edge-high (+ e 1)))) e)))))
;; The same as one list: mask m's edges are mask-edge-list[mask-first[m + 1] ..
;; mask-first[m + 2] - 1] (a numeric loop, no iterator, in the cells' inner loop).
(local (mask-edge-list mask-first)
  (let [all [] first []]
    (each [m edges (ipairs mask-edges)]
      (tset first m (+ 1 (length all)))
      (each [_ e (ipairs edges)] (table.insert all e)))
    (tset first 257 (+ 1 (length all)))
    (values all first)))

(fn find-cells! [state]
  "3. Cells with surface, and their crossing edges (each edge once). Leaves
state.cell-count and, per cell c (1-based), its grid cell in state.cell-i, cell-j,
cell-k, its corners inside as bits (state.cell-mask), its corner values at 8 (c -
1) + corner + 1 of state.cell-v and its local edges' crossings at 12 (c - 1) + edge
+ 1 of state.cell-edges (0: no crossing): flat arrays, no table per cell (a city at
256 cells has 170,000 of them). Leaves state.crossings (their count) and per
crossing its low end (state.ex0, ey0, ez0), its axis (eaxis) and the values at its
ends (ed0, ed1). Makes the estimate exact."
  (let [{: leaves : leaf-halves : corner-values : corner-inside : slot-points : point-count
         : counts : nx : ny : nz} state
        side (+ leaf 1)
        s2 (* side side)
        ;; Each corner's slot from its cell's (see corner-bits).
        corner-slot (fcollect [c 0 7]
                      (let [(x y z) (corner-bits c)] (+ x (* side y) (* s2 z))))
        ;; Crossing edges: 3 p + axis (p their low end's grid point, see
        ;; sample-corners!) -> index; their ends and values.
        edge-index (int-array (* 3 (+ point-count 1)))
        ex0 [] ey0 [] ez0 [] ed0 [] ed1 [] eaxis []
        ;; Calls (fn [l i0 j0 k0 a b c at mask]) for each cell of the leaves' kept
        ;; halves (see cells-of) within the grid, with surface (a corner inside and
        ;; one not), in order; `at` is its low corner's slot.
        each-cell (fn [f]
                    (each [l [i0 j0 k0] (ipairs leaves)]
                      (let [base (* (- l 1) side side side)
                            visit (cells-of (. leaf-halves l))]
                        (for [q 1 (length visit) 3]
                          (let [a (. visit q) b (. visit (+ q 1)) c (. visit (+ q 2))
                                at (+ base 1 a (* side b) (* s2 c))
                                mask (mask-of corner-inside at side s2)]
                            (when (and (< 0 mask 255)
                                       (< (+ i0 a) nx) (< (+ j0 b) ny) (< (+ k0 c) nz))
                              (f (+ i0 a) (+ j0 b) (+ k0 c) at mask)))))))]
    ;; Counted first, so that the cells' arrays are made at their size.
    (var cells 0)
    (each-cell (fn [] (set cells (+ cells 1))))
    (let [cell-i (int-array cells) cell-j (int-array cells) cell-k (int-array cells)
          cell-mask (byte-array cells)
          cell-v (float-array (* 8 cells)) cell-edges (int-array (* 12 cells))]
      (var (crossings c) (values 0 0))
      (each-cell
        (fn [i j k at mask]
          (let [vb (* 8 c) eb (* 12 c)]
            (set c (+ c 1))
            (tset cell-i c i) (tset cell-j c j) (tset cell-k c k) (tset cell-mask c mask)
            ;; (Written out: a loop of eight costs LuaJIT more than its body.)
            (tset cell-v (+ vb 1) (. corner-values at))
            (tset cell-v (+ vb 2) (. corner-values (+ at 1)))
            (tset cell-v (+ vb 3) (. corner-values (+ at side)))
            (tset cell-v (+ vb 4) (. corner-values (+ at side 1)))
            (tset cell-v (+ vb 5) (. corner-values (+ at s2)))
            (tset cell-v (+ vb 6) (. corner-values (+ at s2 1)))
            (tset cell-v (+ vb 7) (. corner-values (+ at s2 side)))
            (tset cell-v (+ vb 8) (. corner-values (+ at s2 side 1)))
            (for [q (. mask-first (+ mask 1)) (- (. mask-first (+ mask 2)) 1)]
              (let [e (. mask-edge-list q)
                    ca (. edge-low (+ e 1))
                    key (+ (. edge-axis (+ e 1))
                           (* 3 (. slot-points (+ at (. corner-slot (+ ca 1))))))]
                (var idx (. edge-index key))
                (when (or (= idx nil) (= idx 0))
                  (set crossings (+ crossings 1))
                  (set idx crossings)
                  (tset edge-index key idx)
                  (tset ex0 idx (+ i (. edge-dx (+ e 1))))
                  (tset ey0 idx (+ j (. edge-dy (+ e 1))))
                  (tset ez0 idx (+ k (. edge-dz (+ e 1))))
                  (tset eaxis idx (. edge-axis (+ e 1)))
                  (tset ed0 idx (. cell-v (+ vb ca 1)))
                  (tset ed1 idx (. cell-v (+ vb (. edge-high (+ e 1)) 1))))
                (tset cell-edges (+ eb e 1) idx))))))
      ;; Each crossing: refine-steps points, 4 for its normal, and about one vertex
      ;; (a cell has about as many crossing edges as a cell has vertices: 3990 and
      ;; 3992 on a sphere), whose distance is checked.
      (set counts.estimate (+ counts.work (* crossings (+ refine-steps 5 state.after))))
      (set (state.cell-count state.crossings) (values cells crossings))
      (set (state.cell-i state.cell-j state.cell-k state.cell-mask state.cell-v state.cell-edges)
           (values cell-i cell-j cell-k cell-mask cell-v cell-edges))
      (set (state.ex0 state.ey0 state.ez0 state.ed0 state.ed1 state.eaxis)
           (values ex0 ey0 ez0 ed0 ed1 eaxis)))))

(fn refine-crossings! [state]
  "4. Crossing points: the linear guess from the corner values, then regula falsi
(the Illinois variant) on the field along each edge. Leaves the points in state.px,
py, pz."
  (let [{: evaluate : crossings : ex0 : ey0 : ez0 : ed0 : ed1 : eaxis : ox : oy : oz : h} state
        px (table-new crossings) py (table-new crossings) pz (table-new crossings)
        ;; Per crossing: the bracket [ta tb] along the edge (0 to 1), the values at
        ;; its ends, the guess ts, and which end the last step kept (1 low, -1 high).
        ta (float-array crossings) tb (float-array crossings)
        fa (float-array crossings) fb (float-array crossings)
        ts (float-array crossings) side-kept (float-array crossings)
        ;; The crossings still moving, first `live` of them (in order).
        active (int-array crossings)
        ;; The points of a round, refilled (evaluate is given their count).
        flat (table-new (* 3 crossings))
        ;; One whose value is within `done` of zero has its point (a plane's, from
        ;; the linear guess: most of a machined part's) and is evaluated no more.
        done (* 1e-6 h)]
    (for [e 1 crossings]
      (let [a (. ed0 e) b (. ed1 e)]
        (tset tb e 1) (tset fa e a) (tset fb e b)
        (tset ts e (+ 0 (* (- 1 0) (/ a (- a b)))))
        (tset active e e)))
    (var live crossings)
    (for [_ 1 refine-steps &until (= 0 live)]
      (for [n 1 live]
        (let [e (. active n) t (. ts e) axis (. eaxis e) q (* 3 (- n 1))]
          (tset flat (+ q 1) (+ ox (* h (+ (. ex0 e) (if (= axis 0) t 0)))))
          (tset flat (+ q 2) (+ oy (* h (+ (. ey0 e) (if (= axis 1) t 0)))))
          (tset flat (+ q 3) (+ oz (* h (+ (. ez0 e) (if (= axis 2) t 0)))))))
      (let [ds (evaluate :crossings flat live)]
        (var still 0)
        (for [n 1 live]
          (let [e (. active n) t (. ts e) d (. ds n)]
            (when (> (abs d) done)
              (set still (+ still 1))
              (tset active still e))
            (if (= (< d 0) (< (. fa e) 0))
                (do (tset ta e t) (tset fa e d)
                    (when (= (. side-kept e) 1) (tset fb e (* 0.5 (. fb e))))
                    (tset side-kept e 1))
                (do (tset tb e t) (tset fb e d)
                    (when (= (. side-kept e) -1) (tset fa e (* 0.5 (. fa e))))
                    (tset side-kept e -1)))
            (tset ts e (if (= d 0) t
                           (let [a (. fa e) b (. fb e) lo (. ta e)]
                             (+ lo (* (- (. tb e) lo) (/ a (- a b)))))))))
        (set live still)))
    (for [e 1 crossings]
      (let [t (. ts e) axis (. eaxis e)]
        (tset px e (+ ox (* h (+ (. ex0 e) (if (= axis 0) t 0)))))
        (tset py e (+ oy (* h (+ (. ey0 e) (if (= axis 1) t 0)))))
        (tset pz e (+ oz (* h (+ (. ez0 e) (if (= axis 2) t 0)))))))
    (set (state.px state.py state.pz) (values px py pz))))

(fn crossing-normals! [state]
  "5. Normals: the field's gradient at each crossing by differences at the four
corners of a tetrahedron around it (k1 = (1 -1 -1), k2 = (-1 -1 1), k3 = (-1 1
-1), k4 = (1 1 1) times the step: the gradient is the sum of each k times the
field there, as accurate as central differences, in four points instead of six),
unit length, in state.nrx, nry, nrz."
  (let [{: evaluate : crossings : px : py : pz : step : ed0 : eaxis} state
        nrx (table-new crossings) nry (table-new crossings) nrz (table-new crossings)
        flat (table-new (* 12 crossings))]
    (for [e 1 crossings]
      (let [x (. px e) y (. py e) z (. pz e)
            b (* 12 (- e 1))]
        (tset flat (+ b 1) (+ x step)) (tset flat (+ b 2) (- y step)) (tset flat (+ b 3) (- z step))
        (tset flat (+ b 4) (- x step)) (tset flat (+ b 5) (- y step)) (tset flat (+ b 6) (+ z step))
        (tset flat (+ b 7) (- x step)) (tset flat (+ b 8) (+ y step)) (tset flat (+ b 9) (- z step))
        (tset flat (+ b 10) (+ x step)) (tset flat (+ b 11) (+ y step)) (tset flat (+ b 12) (+ z step))))
    (let [ds (evaluate :normals flat)]
      (for [e 1 crossings]
        (let [b (* 4 (- e 1))
              d1 (. ds (+ b 1)) d2 (. ds (+ b 2)) d3 (. ds (+ b 3)) d4 (. ds (+ b 4))
              gx (+ d1 (- d2) (- d3) d4)
              gy (+ (- d1) (- d2) d3 d4)
              gz (+ (- d1) d2 (- d3) d4)
              len (sqrt (+ (* gx gx) (* gy gy) (* gz gz)))]
          (if (> len 0)
              (do (tset nrx e (/ gx len)) (tset nry e (/ gy len)) (tset nrz e (/ gz len)))
              ;; A flat spot: the edge's own direction, pointing outward.
              (let [axis (. eaxis e) sgn (if (< (. ed0 e) 0) 1 -1)]
                (tset nrx e (if (= axis 0) sgn 0)) (tset nry e (if (= axis 1) sgn 0))
                (tset nrz e (if (= axis 2) sgn 0)))))))
    (set (state.nrx state.nry state.nrz) (values nrx nry nrz))))

(fn find-patches! [state]
  "6. Patches: each cell's patches (see patches) in state.cell-rep and
state.cell-joined, and in state.cell-flips (by cell) the faces whose decisions were
reversed. Where both cells of an ambiguous face have one patch through both of the
face's segments, the quads of the two segments would share their edge across the
face (four triangles on one edge): reversing the face's decision in both cells
splits each patch in two. Repeated until no face is left so (each reversal only
splits patches, so it ends); counted in state.counts.flipped."
  (let [{: cell-count : cell-i : cell-j : cell-k : cell-v : cell-mask : counts : stride-x : stride-y
         : evaluate : ox : oy : oz : h : nx : ny : nz} state
        ;; Grid cell key -> cell number.
        cell-at {}
        ;; A cell's corner values as patches reads them (one table, refilled).
        corner-scratch [0 0 0 0 0 0 0 0]
        values-of (fn [c]
                    (let [b (* 8 (- c 1))]
                      (for [q 1 8] (tset corner-scratch q (. cell-v (+ b q))))
                      corner-scratch))
        cell-rep (table-new cell-count) cell-joined (table-new cell-count)
        cell-flips {}
        face-key (fn [c fi]
                   (let [axis (floor (/ (- fi 1) 2)) side (% (- fi 1) 2)]
                     (+ axis (* 3 (+ (. cell-i c) (if (= axis 0) side 0)
                                     (* stride-x (+ (. cell-j c) (if (= axis 1) side 0)))
                                     (* stride-y (+ (. cell-k c) (if (= axis 2) side 0))))))))
        ;; The same face seen from the cell across it.
        across (fn [c fi]
                 (let [axis (floor (/ (- fi 1) 2)) sgn (if (= 0 (% (- fi 1) 2)) -1 1)]
                   (values (. cell-at (+ (. cell-i c) (if (= axis 0) sgn 0)
                                         (* stride-x (+ (. cell-j c) (if (= axis 1) sgn 0)))
                                         (* stride-y (+ (. cell-k c) (if (= axis 2) sgn 0)))))
                           (if (= sgn 1) (- fi 1) (+ fi 1)))))
        flip! (fn [c fi]
                (let [flips (or (. cell-flips c) {})]
                  (tset cell-flips c flips)
                  (tset flips fi (not (. flips fi)))
                  (let [(rep joined) (patches (values-of c) flips)]
                    (tset cell-rep c rep)
                    (tset cell-joined c joined))))
        flipped {}
        ;; A share of the leaves (see mesh-shares!) may not have the cell across a
        ;; joined face: it is another share's. Its corners are evaluated here (the
        ;; same numbers as that share's) for its joined faces, as that share finds
        ;; them before any reversal.
        ;; The grid cell across face fi of cell c.
        ghost-cell (fn [c fi]
                     (let [axis (floor (/ (- fi 1) 2)) sgn (if (= 0 (% (- fi 1) 2)) -1 1)]
                       (values (+ (. cell-i c) (if (= axis 0) sgn 0))
                               (+ (. cell-j c) (if (= axis 1) sgn 0))
                               (+ (. cell-k c) (if (= axis 2) sgn 0)))))
        ghost-joined (fn [c fi]
                       (let [(gi gj gk) (ghost-cell c fi)
                             flat []]
                         (for [corner 0 7]
                           (let [(x y z) (corner-bits corner)]
                             (table.insert flat (+ ox (* (min nx (+ gi x)) h)))
                             (table.insert flat (+ oy (* (min ny (+ gj y)) h)))
                             (table.insert flat (+ oz (* (min nz (+ gk z)) h)))))
                         (let [(_ joined) (patches (evaluate :patches flat))] joined)))
        ;; Each cell's joined faces before any reversal.
        first-joined {}]
    (for [c 1 cell-count]
      ;; Most cells' patches are known by their corners' signs alone.
      (case (. plain-patches (. cell-mask c))
        rep (do (tset cell-rep c rep) (tset cell-joined c no-faces))
        _ (let [(rep joined) (patches (values-of c))]
            (tset cell-rep c rep)
            (tset cell-joined c joined))))
    ;; Each reversal takes effect at once: a cell between two such faces
    ;; (a twisted row of cells) must not have both reversed in one pass.
    (var todo (fcollect [c 1 cell-count] (when (< 0 (length (. cell-joined c))) c)))
    ;; The cells by grid position, to find the one across a face: only where a
    ;; face is joined (most meshes have none: a torus, machined-part).
    (when (< 0 (length todo))
      (for [c 1 cell-count]
        (tset cell-at (+ (. cell-i c) (* stride-x (. cell-j c)) (* stride-y (. cell-k c))) c)))
    (each [_ c (ipairs todo)] (tset first-joined c (. cell-joined c)))
    (for [round 1 16 &until (= 0 (length todo))]
      (let [again []
            joined? (fn [c fi] (accumulate [j? false _ g (ipairs (. cell-joined c))] (or j? (= g fi))))]
        (each [_ c (ipairs todo)]
          (each [_ fi (ipairs (icollect [_ g (ipairs (. cell-joined c))] g))]
            (let [(other ofi) (across c fi)]
              ;; The cell across is another share's. Where both cells have this
              ;; face alone joined before any reversal, one process would reverse
              ;; it whatever the order; each share reverses its side (counted
              ;; half each). Anything else (more joined faces, a later round) may
              ;; depend on the order: the share says so (state.met!, see
              ;; mesh-shares!).
              (when (and (not other) state.share? (joined? c fi)
                         (state.cell-kept? (ghost-cell c fi)))
                (if (and (= round 1) (= 1 (length (. first-joined c)))
                         (not (. flipped (face-key c fi))))
                    (let [ghost (ghost-joined c fi)]
                      (if (and (= 1 (length ghost)) (= ofi (. ghost 1)))
                          (do (tset flipped (face-key c fi) true)
                              (set counts.flipped (+ 0.5 (or counts.flipped 0)))
                              (flip! c fi)
                              (table.insert again c))
                          (< 0 (length ghost))
                          (state.met! (ghost-cell c fi))))
                    (state.met! (ghost-cell c fi))))
              (when (and other (joined? c fi) (joined? other ofi)
                         (not (. flipped (face-key c fi))))
                (tset flipped (face-key c fi) true)
                (set counts.flipped (+ 1 (or counts.flipped 0)))
                (flip! c fi)
                (flip! other ofi)
                (table.insert again c)
                (table.insert again other)))))
        (set todo again)))
    (set (state.cell-rep state.cell-joined state.cell-flips)
         (values cell-rep cell-joined cell-flips))))

(fn separate! [placed lx ly lz h]
  "Patches of one cell (their vertices `placed`, each [x y z mx my mz] with the
crossings' mean; the cell's low corner lx ly lz) whose vertices meet: each moves
toward its crossings' mean (or, when that is the same point, apart along x)."
  (for [a 1 (length placed)]
    (for [b (+ a 1) (length placed)]
      (let [[ax ay az] (. placed a) [bx by bz] (. placed b)]
        (when (< (sqrt (+ (* (- ax bx) (- ax bx)) (* (- ay by) (- ay by))
                          (* (- az bz) (- az bz))))
                 (* inset h))
          (each [k q (ipairs [(. placed a) (. placed b)])]
            (let [[x y z mx my mz] q
                  dx (- mx x) dy (- my y) dz (- mz z)
                  len (sqrt (+ (* dx dx) (* dy dy) (* dz dz)))
                  push (* 10 inset h)
                  (ux uy uz) (if (> len (* inset h)) (values (/ dx len) (/ dy len) (/ dz len))
                                 (values (if (= k 1) -1 1) 0 0))]
              (tset q 1 (clamp-cell (+ x (* push ux)) lx h))
              (tset q 2 (clamp-cell (+ y (* push uy)) ly h))
              (tset q 3 (clamp-cell (+ z (* push uz)) lz h)))))))))

(local single-patches (setmetatable {} {:__mode :k}))

(fn single-patch? [rep]
  "Whether a cell's patches (see patches) are one: all its crossing edges share a
representative. Remembered per table: most cells share plain-patches' few."
  (let [known (. single-patches rep)]
    (if (not= nil known) known
        (let [r1 (. rep (next rep))
              one? (accumulate [one? true _ r (each-pair rep)] (and one? (= r r1)))]
          (tset single-patches rep one?)
          one?))))

(fn place-vertices! [state]
  "7. One vertex per patch of each cell (see qef-vertex and separate!). Leaves
state.positions [x y z ...], state.vertex-info (per vertex its cell's low corner and
its crossings' mean, six numbers) and state.quad-vertices (per crossing, the
vertices of its four cells' patches through it, in the order of make-triangles);
drops the cells' values, edges and patches."
  (let [{: cell-count : cell-i : cell-j : cell-k : cell-edges : cell-rep : cell-mask
         : px : py : pz : nrx : nry : nrz : ox : oy : oz : h : eaxis : crossings} state
        positions []
        vertex-info []
        shared {}
        ;; A cell's crossings, in the order of its edges (refilled per cell).
        ids [0 0 0 0 0 0 0 0 0 0 0 0]
        quad-vertices (table-new (* 4 crossings))
        ;; The vertex of local edge e, whose crossing is idx, in its quad.
        put! (fn [e idx v]
               (tset quad-vertices (+ (* 4 (- idx 1)) (. edge-slot (+ e 1))) v))
        add! (fn [n x y z lx ly lz mx my mz]
               ;; Vertex n: its position and info.
               (let [b (* 3 (- n 1)) i (* 6 (- n 1))]
                 (tset positions (+ b 1) x) (tset positions (+ b 2) y)
                 (tset positions (+ b 3) z)
                 (tset vertex-info (+ i 1) lx) (tset vertex-info (+ i 2) ly)
                 (tset vertex-info (+ i 3) lz) (tset vertex-info (+ i 4) mx)
                 (tset vertex-info (+ i 5) my) (tset vertex-info (+ i 6) mz)))]
    (var vertex-count 0)
    (for [c 1 cell-count]
      (let [rep (. cell-rep c)
            eb (* 12 (- c 1))
            lx (+ ox (* (. cell-i c) h)) ly (+ oy (* (. cell-j c) h)) lz (+ oz (* (. cell-k c) h))]
        (if (single-patch? rep)
            ;; One patch (most cells): its vertex, with no grouping. Its crossing
            ;; edges are its mask's (3 to 6 of the 12: a loop over those only).
            (let [mask (. cell-mask c)
                  first (. mask-first (+ mask 1)) last (- (. mask-first (+ mask 2)) 1)]
              (for [q first last]
                (tset ids (+ 1 (- q first)) (. cell-edges (+ eb 1 (. mask-edge-list q)))))
              (let [(x y z mx my mz) (qef-vertex ids 1 (+ 1 (- last first))
                                                 px py pz nrx nry nrz lx ly lz h)]
                (set vertex-count (+ vertex-count 1))
                (add! vertex-count x y z lx ly lz mx my mz)
                (for [q first last]
                  (let [e (. mask-edge-list q)]
                    (put! e (. cell-edges (+ eb e 1)) vertex-count)))))
            (let [groups {}
                  order []
                  local-vertex {}]
              (for [e 0 11]
                (let [r (. rep e)]
                  (when r
                    (when (not (. groups r))
                      (tset groups r [])
                      (table.insert order r))
                    (table.insert (. groups r) (. cell-edges (+ eb e 1))))))
              (let [placed (icollect [_ r (ipairs order)]
                             [(qef-vertex (. groups r) 1 (length (. groups r))
                                          px py pz nrx nry nrz lx ly lz h)])]
                ;; Two or more patches in one cell (a feature thinner than a cell,
                ;; two objects close together): their tangent planes meet anywhere
                ;; in the cell, and a vertex there, or pulled onto the nearest
                ;; surface, may lie beyond the other patch, whose triangles its own
                ;; then cross (48 crossing pairs on flower at 128 cells, all in such
                ;; cells). Each goes to its crossings' mean instead, on its own side
                ;; of the others, and moves onto the surface only nearer that mean
                ;; than the others' (see project-vertices!).
                (each [_ q (ipairs placed)]
                  (for [k 1 3] (tset q k (. q (+ k 3)))))
                (separate! placed lx ly lz h)
                (each [n r (ipairs order)]
                  (let [[x y z mx my mz] (. placed n)]
                    (set vertex-count (+ vertex-count 1))
                    (tset shared vertex-count [(+ (- vertex-count n) 1)
                                               (+ (- vertex-count n) (length order))])
                    (add! vertex-count x y z lx ly lz mx my mz)
                    (tset local-vertex r vertex-count))))
              (for [e 0 11]
                (let [idx (. cell-edges (+ eb e 1))]
                  (when (not= idx 0) (put! e idx (. local-vertex (. rep e))))))))))
    ;; Done with the cells but for their grid positions: the rest may go.
    (set (state.cell-v state.cell-edges state.cell-rep state.cell-joined state.cell-flips) nil)
    (set (state.positions state.vertex-info state.quad-vertices state.shared-cell)
         (values positions vertex-info quad-vertices shared))))

(fn project-vertices! [state]
  "8. Vertices off the surface (see off-surface): each moved to the best of a
Newton step along the field's gradient (kept in its cell) and its crossings' mean
(which may leave the cell, but a crossing is on the surface), where it stays unless
that is nearer the surface. Moves them in state.positions; counts them in
state.counts.moved."
  (let [{: evaluate : counts : positions : vertex-info : shared-cell : h : step} state
        flat (icollect [_ v (ipairs positions)] v)
        ds (evaluate :projection flat)
        bad (icollect [v d (ipairs ds)] (when (> (abs d) (* off-surface h)) v))
        ;; A vertex of a cell with several patches (see place-vertices!) moves
        ;; only to a point nearer its own crossings' mean than to the other
        ;; patches': the nearest surface may be another patch's.
        own-side? (fn [v x y z]
                    (case (. shared-cell v)
                      [first last]
                      (let [mean-gap (fn [w]
                                       (let [i (* 6 (- w 1))]
                                         (+ (^ (- x (. vertex-info (+ i 4))) 2)
                                            (^ (- y (. vertex-info (+ i 5))) 2)
                                            (^ (- z (. vertex-info (+ i 6))) 2))))
                            own (mean-gap v)]
                        (faccumulate [ok? true w first last]
                          (and ok? (or (= w v) (< own (mean-gap w))))))
                      _ true))
        grad []]
    (each [_ v (ipairs bad)]
      (let [b (* 3 (- v 1))
            x (. positions (+ b 1)) y (. positions (+ b 2)) z (. positions (+ b 3))]
        (each [_ [dx dy dz] (ipairs [[step 0 0] [(- step) 0 0] [0 step 0]
                                     [0 (- step) 0] [0 0 step] [0 0 (- step)]])]
          (table.insert grad (+ x dx)) (table.insert grad (+ y dy))
          (table.insert grad (+ z dz)))))
    (let [gs (evaluate :projection grad)
          candidates []]
      (each [n v (ipairs bad)]
        (let [b (* 3 (- v 1)) g (* 6 (- n 1))
              gx (- (. gs (+ g 1)) (. gs (+ g 2)))
              gy (- (. gs (+ g 3)) (. gs (+ g 4)))
              gz (- (. gs (+ g 5)) (. gs (+ g 6)))
              len (sqrt (+ (* gx gx) (* gy gy) (* gz gz)))
              d (. ds v)
              s (if (> len 0) (/ d len) 0)
              clamp (fn [q lo] (clamp-cell q lo h))
              i (* 6 (- v 1))]
          (table.insert candidates (clamp (- (. positions (+ b 1)) (* s gx)) (. vertex-info (+ i 1))))
          (table.insert candidates (clamp (- (. positions (+ b 2)) (* s gy)) (. vertex-info (+ i 2))))
          (table.insert candidates (clamp (- (. positions (+ b 3)) (* s gz)) (. vertex-info (+ i 3))))
          (for [q 4 6] (table.insert candidates (. vertex-info (+ i q))))))
      (let [cds (evaluate :projection candidates)]
        (each [n v (ipairs bad)]
          (var best (abs (. ds v)))
          (for [c 0 1]
            (let [at (+ (* 2 (- n 1)) c 1)
                  k (* 3 (- at 1))]
              (when (and (< (abs (. cds at)) best)
                         (own-side? v (. candidates (+ k 1)) (. candidates (+ k 2))
                                    (. candidates (+ k 3))))
                (set best (abs (. cds at)))
                (for [q 1 3]
                  (tset positions (+ (* 3 (- v 1)) q)
                        (. candidates (+ (* 3 (- at 1)) q))))))))))
    (set counts.moved (length bad))))

(fn make-triangles [state]
  "9. A quad of the four cells around each crossing edge, split into two triangles
along the diagonal that bends it least: the triangles [a b c ...], counter-clockwise
seen from outside."
  (let [{: crossings : positions : quad-vertices : ex0 : ey0 : ez0 : ed0} state
        triangles (table-new (* 6 crossings))
        ;; The unit normal of triangle a b c (0 0 0 when degenerate).
        normal (fn [a b c]
                 (let [pa (* 3 (- a 1)) pb (* 3 (- b 1)) pc (* 3 (- c 1))
                       ax (. positions (+ pa 1)) ay (. positions (+ pa 2)) az (. positions (+ pa 3))
                       ux (- (. positions (+ pb 1)) ax) uy (- (. positions (+ pb 2)) ay)
                       uz (- (. positions (+ pb 3)) az)
                       vx (- (. positions (+ pc 1)) ax) vy (- (. positions (+ pc 2)) ay)
                       vz (- (. positions (+ pc 3)) az)
                       x (- (* uy vz) (* uz vy)) y (- (* uz vx) (* ux vz))
                       z (- (* ux vy) (* uy vx))
                       l (sqrt (+ (* x x) (* y y) (* z z)))]
                   (if (> l 0) (values (/ x l) (/ y l) (/ z l)) (values 0 0 0))))
        flatness (fn [a b c d]
                   (let [(x1 y1 z1) (normal a b c) (x2 y2 z2) (normal a c d)]
                     (+ (* x1 x2) (* y1 y2) (* z1 z2))))]
    (for [e 1 crossings]
      ;; The vertices of the cells at offsets (du dv) in {-1 0}^2 along the two
      ;; other axes u, v (u x v = the edge's axis), counter-clockwise:
      ;; (-1 -1) (0 -1) (0 0) (-1 0) (see edge-slot).
      (let [q (* 4 (- e 1))
            q1 (. quad-vertices (+ q 1)) q2 (. quad-vertices (+ q 2))
            q3 (. quad-vertices (+ q 3)) q4 (. quad-vertices (+ q 4))
            _ (assert (and q1 q2 q3 q4)
                      (string.format "mesh: crossing edge without cell (%d %d %d)"
                                     (. ex0 e) (. ey0 e) (. ez0 e)))
            (a b c d) (if (< (. ed0 e) 0) (values q1 q2 q3 q4) (values q4 q3 q2 q1))
            t (* 6 (- e 1))]
        (if (>= (flatness a b c d) (flatness b c d a))
            (do (tset triangles (+ t 1) a) (tset triangles (+ t 2) b) (tset triangles (+ t 3) c)
                (tset triangles (+ t 4) a) (tset triangles (+ t 5) c) (tset triangles (+ t 6) d))
            (do (tset triangles (+ t 1) b) (tset triangles (+ t 2) c) (tset triangles (+ t 3) d)
                (tset triangles (+ t 4) b) (tset triangles (+ t 5) d) (tset triangles (+ t 6) a)))))
    triangles))

;; A vertex farther than this (in cells) from its crossings' mean is one the QEF
;; placed at a sharp feature or clamped to its cell: the crossings that survive one
;; vertex per patch at the mean in cells of several (see place-vertices!) are all
;; between triangles with such a vertex (0.48 cells and more on flower at 48,
;; platonic-shelf at 64 and custom at 96), and only those triangles are checked.
(local off-mean 0.25)
;; Rounds of untangle!: each moves the vertices of the pairs still crossing.
(local untangle-rounds 4)

(fn untangle! [state triangles]
  "10. Triangles that still cross (src/mesh/intersect.fnl, by more than 1e-6
cells): the vertices of both go to their crossings' mean (where a mesher that
keeps no sharp feature puts them), and the triangles of the vertices moved are
checked again, for a few rounds. Checks only triangles with a vertex more than
off-mean from its mean. A pair sharing a corner that overlaps beyond it (a fold)
moves all its vertices so; a crossing pair those that are off. Moves them in
state.positions; counts the vertices moved in counts.untangled and the pairs left
crossing or folded in counts.crossing."
  (let [{: positions : vertex-info : h : counts} state
        nv (/ (length positions) 3)
        nt (/ (length triangles) 3)
        m {: positions : triangles}
        off? (fn [v]
               (let [b (* 3 (- v 1)) i (* 6 (- v 1))
                     dx (- (. positions (+ b 1)) (. vertex-info (+ i 4)))
                     dy (- (. positions (+ b 2)) (. vertex-info (+ i 5)))
                     dz (- (. positions (+ b 3)) (. vertex-info (+ i 6)))]
                 (> (+ (* dx dx) (* dy dy) (* dz dz)) (* off-mean off-mean h h))))
        triangles-of (fn [vs]
                       ;; The triangles with a vertex in the set vs (1-based).
                       (let [out {}]
                         (for [t 1 nt]
                           (for [c 1 3]
                             (when (. vs (. triangles (+ (* 3 (- t 1)) c)))
                               (tset out t true))))
                         out))
        risky {}]
    (for [v 1 nv] (when (off? v) (tset risky v true)))
    ;; Crossings among the triangles of risky vertices; folds around every vertex
    ;; (intersect.folds: a vertex's own triangles, cheap), in later rounds around
    ;; those of the triangles moved.
    (var (only fold-only first?) (values (when (next risky) (triangles-of risky)) nil true))
    (var (rounds moved left) (values 0 0 0))
    (while (or only first?)
      (let [tick (fn [] (worked! state :untangle 0))
            r (if (and only (next only))
                  (intersect.self-intersections m {:min-length (* 1e-6 h) :max-list math.huge
                                                    :only only :folds? false : tick})
                  {:pairs 0 :list []})
            fold-list (intersect.folds m {:min-length (* 1e-6 h) :only fold-only : tick})
            changed {}]
        (set (only first? left rounds) (values nil false (+ r.pairs (length fold-list)) (+ rounds 1)))
        (when (<= rounds untangle-rounds)
          (each [_ [s t fold?] (ipairs (icollect [_ [a b] (ipairs fold-list)
                                                  &into (icollect [_ p (ipairs r.list)] p)]
                                          [a b true]))]
            (each [_ tri (ipairs [s t])]
              (for [c 1 3]
                (let [v (. triangles (+ (* 3 tri) c))]
                  ;; A fold at a shared vertex: its triangles' vertices were where
                  ;; the QEF put a sharp feature (near their means, not off);
                  ;; at the means the sheet is smooth there.
                  (when (or fold? (off? v))
                    (tset changed v true)
                    (set moved (+ moved 1))
                    (for [q 1 3]
                      (tset positions (+ (* 3 (- v 1)) q) (. vertex-info (+ (* 6 (- v 1)) 3 q)))))))))
          (when (next changed)
            (set only (triangles-of changed))
            (set fold-only {})
            (each [t (each-pair only)]
              (for [c 1 3] (tset fold-only (. triangles (+ (* 3 (- t 1)) c)) true)))))))
    (set (counts.untangled counts.crossing) (values moved left))))

(fn local-steps! [state]
  "Steps 2 to 8 on state.leaves: the cells' vertices, and the crossings' quads."
  (mark! state :corners)
  (sample-corners! state)
  (mark! state :cells)
  (find-cells! state)
  ;; What each step leaves that no later one reads goes at once: the peak is
  ;; the cells, crossings and vertices together (a box at 256 cells: 256 MB live
  ;; keeping them to the end).
  (set (state.corner-values state.corner-inside state.slot-points) (values nil nil nil))
  (mark! state :crossings)
  (refine-crossings! state)
  (set state.ed1 nil)
  (mark! state :normals)
  (crossing-normals! state)
  (worked! state :patches (* 0.25 geometry-work state.crossings))
  (mark! state :patches)
  (find-patches! state)
  (worked! state :vertices (* 0.25 geometry-work state.crossings))
  (mark! state :vertices)
  (place-vertices! state)
  ;; (The crossings' axes stay: a share's result names its crossings by them.)
  (set (state.px state.py state.pz state.nrx state.nry state.nrz)
       (values nil nil nil nil nil nil))
  (set (state.cell-i state.cell-j state.cell-k) (values nil nil nil))
  (worked! state :projection (* 0.2 geometry-work state.crossings))
  (mark! state :projection)
  (project-vertices! state))

;;; Every core: the leaves in shares, one a process (src/util/fork.fnl), each share
;;; taken through steps 2 to 8 alone, their crossings and vertices then merged.

;; Leaves a share has at least: fewer take less time than a fork (a torus at 128
;; cells: 3229 leaves, about 20 microseconds each), and a share's border with the
;; next is worked on by both.
(local min-share-leaves 256)
;; From this many leaves (about 256 cells), this process's heap is collected
;; before the shares are forked, and theirs are then collected as they go (see
;; fork.run-shares): a collection costs milliseconds, a share's garbage kept to
;; its end hundreds of MB at 512 cells.
(local collect-leaves 8192)
;; Shares per process (see mesh-shares!). More would let a process that is done
;; take the share of one held up (an expensive object in it), but each share costs
;; its process new traces (LuaJIT specialises them on the closures a share makes):
;; with 4 a process, a torus at 128 cells took 0.104 s, with 2 0.092, with 1 0.088
;; (median of 7); custom, flower, organic and platonic-shelf at 256 were as fast or
;; faster with 1 than 2.
(local shares-per-worker 1)
;; Numbers before a share's crossings, per crossing and per vertex (see
;; share-numbers).
(local share-header 10)
(local crossing-width 9)
(local vertex-width 9)

(fn use-shares? [state]
  "Whether steps 2 to 8 go to shares: a field that may run in a child (:fork-safe?,
the CPU evaluator's, not the GPU's), and enough leaves for more than one share
(state.grid.workers, default every core)."
  (let [workers (or state.grid.workers (fork.cores))]
    (and state.field.fork-safe? (not (fork.child?)) (< 1 workers)
         (<= (* 2 (or state.grid.share-leaves min-share-leaves)) (length state.leaves)))))

(fn share-numbers [state ?out ?room]
  "A share's result as one list of numbers, in ?out (an FFI double array with ?room
places from 1) where they fit, else in a new one; returns the list and their count.
They are its counts (cells, crossings, vertices, flipped, moved, points, work,
estimate), the first and last share it would have to be taken with (0 0: none; see
mesh-shares!), then per
crossing its low end, axis, value there and its quad's four vertices (0: a cell of
another share), then per vertex its position and info."
  (let [{: crossings : positions : vertex-info : quad-vertices
         : ex0 : ey0 : ez0 : eaxis : ed0 : counts} state
        vertices (/ (length positions) 3)
        n (+ share-header (* crossing-width crossings) (* vertex-width vertices))
        out (if (and ?out (<= n ?room)) ?out (float-array n))]
    (each [q v (ipairs [state.cell-count crossings vertices (or counts.flipped 0)
                        (or counts.moved 0) counts.points counts.work counts.estimate
                        (or state.met-lo 0) (or state.met-hi 0)])]
      (tset out q v))
    (for [e 1 crossings]
      (let [o (+ share-header (* crossing-width (- e 1))) q (* 4 (- e 1))]
        (tset out (+ o 1) (. ex0 e)) (tset out (+ o 2) (. ey0 e)) (tset out (+ o 3) (. ez0 e))
        (tset out (+ o 4) (. eaxis e)) (tset out (+ o 5) (. ed0 e))
        (tset out (+ o 6) (or (. quad-vertices (+ q 1)) 0))
        (tset out (+ o 7) (or (. quad-vertices (+ q 2)) 0))
        (tset out (+ o 8) (or (. quad-vertices (+ q 3)) 0))
        (tset out (+ o 9) (or (. quad-vertices (+ q 4)) 0))))
    (let [o (+ share-header (* crossing-width crossings))]
      (for [v 1 vertices]
        (let [b (+ o (* vertex-width (- v 1))) p (* 3 (- v 1)) i (* 6 (- v 1))]
          (tset out (+ b 1) (. positions (+ p 1))) (tset out (+ b 2) (. positions (+ p 2)))
          (tset out (+ b 3) (. positions (+ p 3)))
          (tset out (+ b 4) (. vertex-info (+ i 1))) (tset out (+ b 5) (. vertex-info (+ i 2)))
          (tset out (+ b 6) (. vertex-info (+ i 3))) (tset out (+ b 7) (. vertex-info (+ i 4)))
          (tset out (+ b 8) (. vertex-info (+ i 5))) (tset out (+ b 9) (. vertex-info (+ i 6))))))
    (values out n)))

(fn merge-shares! [state results]
  "The shares' results, in the order of their leaves, as one mesher's: vertices
numbered on, a crossing that shares meet at (one whose quad has a cell in another
share) made one, numbered where the first share met it (as one process would
have), its quad's vertices from each share. A result is a share's numbers (see
share-numbers) or, run here, its state; the first one's arrays, if a state, are
taken as they are and added to. Leaves in state what steps 2 to 8 leave."
  (let [{: stride-x : stride-y : counts} state
        first (. results 1 1)
        own (when (= (type first) :table) first)
        numbers (icollect [k [r] (ipairs results)]
                  (when (not (and own (= k 1)))
                    (if (= (type r) :table) (share-numbers r) r)))
        ;; At most the shares' crossings, and their vertices.
        most (accumulate [n (if own own.crossings 0) _ a (ipairs numbers)] (+ n (. a 2)))
        all (accumulate [n (if own (/ (length own.positions) 3) 0) _ a (ipairs numbers)]
              (+ n (. a 3)))
        positions (if own own.positions (table-new (* 3 all)))
        vertex-info (if own own.vertex-info (table-new (* 6 all)))
        quad-vertices (if own own.quad-vertices (table-new (* 4 most)))
        ex0 (table-new most) ey0 (table-new most) ez0 (table-new most)
        eaxis (table-new most) ed0 (table-new most)
        ;; Crossing key -> number, for those a share had only part of the quad of.
        open {}]
    (var (nc nv cells) (values 0 0 0))
    (set (counts.flipped counts.moved counts.estimate) (values 0 0 counts.work))
    (when own
      (let [c own.counts]
        (set nc own.crossings)
        (set nv (/ (length own.positions) 3))
        (set cells own.cell-count)
        (set counts.flipped (+ counts.flipped (or c.flipped 0)))
        (set counts.moved (+ counts.moved (or c.moved 0)))
        (set counts.points (+ counts.points c.points))
        (set counts.work (+ counts.work c.work))
        (set counts.estimate (+ counts.estimate c.estimate))
        (for [e 1 nc]
          (let [q (* 4 (- e 1)) gi (. own.ex0 e) gj (. own.ey0 e) gk (. own.ez0 e)
                axis (. own.eaxis e)]
            (tset ex0 e gi) (tset ey0 e gj) (tset ez0 e gk) (tset eaxis e axis)
            (tset ed0 e (. own.ed0 e))
            (when (not (and (. quad-vertices (+ q 1)) (. quad-vertices (+ q 2))
                            (. quad-vertices (+ q 3)) (. quad-vertices (+ q 4))))
              (tset open (+ axis (* 3 (+ gi (* stride-x gj) (* stride-y gk)))) e))))))
    (each [_ a (ipairs numbers)]
      (let [crossings (. a 2) vertices (. a 3)]
        (set cells (+ cells (. a 1)))
        (set counts.flipped (+ counts.flipped (. a 4)))
        (set counts.moved (+ counts.moved (. a 5)))
        (set counts.points (+ counts.points (. a 6)))
        (set counts.work (+ counts.work (. a 7)))
        (set counts.estimate (+ counts.estimate (. a 8)))
        (for [e 1 crossings]
          (let [o (+ share-header (* crossing-width (- e 1)))
                gi (. a (+ o 1)) gj (. a (+ o 2)) gk (. a (+ o 3)) axis (. a (+ o 4))
                whole? (and (not= 0 (. a (+ o 6))) (not= 0 (. a (+ o 7)))
                            (not= 0 (. a (+ o 8))) (not= 0 (. a (+ o 9))))
                key (when (not whole?) (+ axis (* 3 (+ gi (* stride-x gj) (* stride-y gk)))))
                known (when key (. open key))
                g (or known (+ nc 1))]
            (when (not known)
              (set nc g)
              (tset ex0 g gi) (tset ey0 g gj) (tset ez0 g gk) (tset eaxis g axis)
              (tset ed0 g (. a (+ o 5)))
              (when key (tset open key g)))
            ;; (Written out: a loop of four, a short inner loop, costs LuaJIT
            ;; more than its body.)
            (let [q (* 4 (- g 1))
                  v1 (. a (+ o 6)) v2 (. a (+ o 7)) v3 (. a (+ o 8)) v4 (. a (+ o 9))]
              (when (not= v1 0) (tset quad-vertices (+ q 1) (+ nv v1)))
              (when (not= v2 0) (tset quad-vertices (+ q 2) (+ nv v2)))
              (when (not= v3 0) (tset quad-vertices (+ q 3) (+ nv v3)))
              (when (not= v4 0) (tset quad-vertices (+ q 4) (+ nv v4))))))
        (let [o (+ share-header (* crossing-width crossings))]
          (for [v 1 vertices]
            (let [b (+ o (* vertex-width (- v 1)))
                  p (* 3 (+ nv v -1)) i (* 6 (+ nv v -1))]
              (tset positions (+ p 1) (. a (+ b 1))) (tset positions (+ p 2) (. a (+ b 2)))
              (tset positions (+ p 3) (. a (+ b 3)))
              (tset vertex-info (+ i 1) (. a (+ b 4))) (tset vertex-info (+ i 2) (. a (+ b 5)))
              (tset vertex-info (+ i 3) (. a (+ b 6))) (tset vertex-info (+ i 4) (. a (+ b 7)))
              (tset vertex-info (+ i 5) (. a (+ b 8))) (tset vertex-info (+ i 6) (. a (+ b 9))))))
        (set nv (+ nv vertices))))
    (set (state.cell-count state.crossings state.positions state.vertex-info state.quad-vertices)
         (values cells nc positions vertex-info quad-vertices))
    (set (state.ex0 state.ey0 state.ez0 state.eaxis state.ed0)
         (values ex0 ey0 ez0 eaxis ed0))))

(fn settle-runs [runs met take]
  "Runs of shares [lo hi result] (disjoint, in order) with none left that met
another: a run whose result met shares a to b ((met result) -> a b, 0 0 for none)
is replaced, with every run it then meets, by one run over them all, whose result
is (take lo hi); until no run meets another. Returns the runs, in order."
  (var runs runs)
  (var again (accumulate [r nil _ run (ipairs runs)] (or r (when (< 0 (met (. run 3))) run))))
  (while again
    (let [[lo hi a] again
          (met-lo met-hi) (met a)
          ;; The runs it meets, whole (runs are disjoint and in order, so one pass
          ;; covers them).
          (lo hi) (accumulate [(l h) (values (min lo met-lo) (max hi met-hi))
                               _ [rlo rhi] (ipairs runs)]
                    (if (and (<= rlo h) (>= rhi l)) (values (min l rlo) (max h rhi))
                        (values l h)))
          kept (icollect [_ run (ipairs runs)]
                 (when (or (< (. run 2) lo) (> (. run 1) hi)) run))]
      (table.insert kept [lo hi (take lo hi)])
      (table.sort kept (fn [x y] (< (. x 1) (. y 1))))
      (set runs kept)
      (set again (accumulate [r nil _ run (ipairs runs)] (or r (when (< 0 (met (. run 3))) run))))))
  runs)

(fn mesh-shares! [state]
  "Steps 2 to 8 with the leaves in shares, taken by as many processes as there are
cores (fork.run-shares); the shares this process takes tell progress. A share that
met a face it could not decide alone (see find-patches!) is taken again here, as
one with the shares up to the one across, until none is left so. Then the shares'
results are merged (merge-shares!)."
  (mark! state nil)
  (let [{: leaves : leaf-halves : field : grid : counts : stride-x : stride-y} state
        workers (or grid.workers (fork.cores))
        shares (min (* shares-per-worker workers)
                    (floor (/ (length leaves) (or grid.share-leaves min-share-leaves))))
        size (/ (length leaves) shares)
        first-of (fn [s] (+ 1 (floor (* (- s 1) size))))
        last-of (fn [s] (if (= s shares) (length leaves) (floor (* s size))))
        ;; Each leaf's number, by the leaf's position; its share.
        leaf-at (collect [l [i j k] (ipairs leaves)] (+ i (* stride-x j) (* stride-y k)) l)
        share-of (fn [l] (faccumulate [found nil s 1 shares]
                           (or found (when (<= (first-of s) l (last-of s)) s))))
        ;; The leaf of grid cell (i j k), if sampled, and the cell's half.
        leaf-of (fn [i j k]
                  (let [a (% i leaf) b (% j leaf) c (% k leaf)]
                    (values (. leaf-at (+ (- i a) (* stride-x (- j b)) (* stride-y (- k c))))
                            (. cell-half (+ 1 a (* leaf b) (* leaf leaf c))))))
        ;; The most numbers a share's result may have: per leaf, 64 cells of 12
        ;; crossings and 4 vertices each (only what is written takes memory).
        room (+ share-header (* (+ (* crossing-width 12) (* vertex-width 4)) leaf leaf leaf
                                (+ 1 (floor size))))
        ;; Progress: this process's shares stand for the others' (each process
        ;; takes the next share as it gets free); shown as a share of the shares.
        (blocks-work blocks-points) (values counts.work counts.points)
        scale (* 1000 shares)]
    (var (own-done own-points) (values 0 0))
    (fn run-range [lo hi ?out ?room]
      ;; Shares lo to hi as one; see share-numbers.
      (let [progress (when (not (fork.child?))
                       (fn [phase work estimate points]
                         (let [part (if (and estimate (< 0 estimate)) (min 1 (/ work estimate)) 0)]
                           (state.progress phase
                                           (+ blocks-work (* scale (min 0.99 (/ (* workers (+ own-done part)) shares))))
                                           (+ blocks-work scale)
                                           (+ blocks-points own-points points)))))
            share (new-state field grid progress)]
        (set share.share? true)
        (set share.leaves (fcollect [l (first-of lo) (last-of hi)] (. leaves l)))
        (set share.leaf-halves (fcollect [l (first-of lo) (last-of hi)] (. leaf-halves l)))
        ;; Whether grid cell (i j k) is in a sampled half of a leaf (then one
        ;; process would have it, see find-patches!).
        (set share.cell-kept?
             (fn [i j k]
               (case (leaf-of i j k)
                 (l half) (not= 0 (bit.band (. leaf-halves l) half))
                 _ false)))
        ;; A face the share could not decide: the share of the cell across.
        (set share.met!
             (fn [i j k]
               (let [other (share-of (leaf-of i j k))]
                 (set share.met-lo (min other (or share.met-lo lo)))
                 (set share.met-hi (max other (or share.met-hi hi))))))
        (local-steps! share)
        (mark! share nil)
        (when (not (fork.child?))
          (set (own-done own-points) (values (+ own-done 1) (+ own-points share.counts.points)))
          ;; The seconds of this process's shares stand for the steps'.
          (each [step t (each-pair share.times)]
            (tset state.times step (+ t (or (. state.times step) 0)))))
        ;; Run here, the share itself (merge-shares! takes it as it is).
        (if ?out (share-numbers share ?out ?room) share)))
    (fork.run-shares
      shares room
      (fn [s ?out ?room] (run-range s s ?out ?room))
      (fn [results]
        (mark! state :merge)
        ;; Runs of shares [lo hi result], in order; a result met shares a to b
        ;; (see share-numbers), 0 0 for none.
        (let [met (fn [r] (if (= (type r) :table)
                              (values (or r.met-lo 0) (or r.met-hi 0))
                              (values (. r 9) (. r 10))))
              runs (settle-runs (fcollect [s 1 shares] [s s (. results s 1)]) met
                                (fn [lo hi]
                                  (set counts.retaken (+ 1 (or counts.retaken 0)))
                                  (let [whole (run-range lo hi)]
                                    ;; (All the shares as one meet no other.)
                                    (when (and (= lo 1) (= hi shares)) (set whole.met-lo nil))
                                    whole)))]
          (merge-shares! state (icollect [_ [_ _ a] (ipairs runs)] [a]))
          (set counts.shares (length runs)))
        true)
      ;; A large mesh's shares keep their heaps in bounds (see fork.run-shares).
      (<= collect-leaves (length leaves))
      ;; Waiting for the others: progress still heard (a stop asked for is seen).
      (fn [] (state.progress :shares (+ blocks-work (* 0.99 scale)) (+ blocks-work scale)
                             (+ blocks-points own-points))))))

(fn mesh [field grid ?progress]
  "Contour `field` over `grid`. The field: {:distances (fn [flat n ?skip]) -> n
signed distances at the points of the flat list x1 y1 z1 x2 ... after its first
?skip (default 0); :step the gradient's
difference step as a share of a cell; :offset (default 0) a share of a cell
added to every value: the level set meshed is the field's at minus that, see
src/mesh/scene.fnl; :fork-safe? true where it may run in a forked child (then
the leaves are shared among processes, see mesh-shares!)}. The grid: {:lo [x y z]
(its low corner) :h (the side of a cell) :dims [nx ny nz] (cells) :cut {:lo :hi} (a
box inside the grid by at least one cell: the field is cut by it, which closes the
mesh) :max-leaves (if given, the most leaf blocks to sample: past it, once the
octree has found them and before any corner is sampled, mesh raises {:leaves n
:max-leaves m}) :workers (processes for the shares, default one a core; 1: none)
:share-leaves (the fewest leaves a share has, default min-share-leaves)}. The mesh
is the same whatever the workers and shares.
`?progress` (fn [phase work estimate points]) hears of each batch of points and
each step: the phase (:blocks, :corners, :crossings, :normals, :patches, :vertices,
:projection, :untangle, :faces), the work done so far (in field evaluations: see geometry-work),
an estimate of all the work (nil until the blocks are known; the grid's :after-work
per vertex included) and the points evaluated.
Returns {:positions [x y z ...] :triangles [a b c ...] (1-based vertex indices,
counter-clockwise seen from outside) :stats {:points (field evaluations) :blocks
(leaf blocks sampled) :skipped (leaf blocks' worth of volume skipped) :cells
(cells with surface) :crossings :flipped (ambiguous faces reversed) :moved (vertices
moved onto the surface) :collections (full collections of the Lua heap, see
bound-heap!) :untangled (vertices moved to their crossings' mean, see untangle!)
:crossing (pairs of triangles left crossing or folded) :times (CPU seconds per step,
of this process's shares) :work :estimate :shares (runs of leaves merged, 1 for
none) :retaken (shares taken again, see mesh-shares!)}}."
  (let [state (new-state field grid ?progress)
        counts state.counts]
    (mark! state :blocks)
    (find-leaves! state)
    (when (and grid.max-leaves (> (length state.leaves) grid.max-leaves))
      (error {:leaves (length state.leaves) :max-leaves grid.max-leaves}))
    (if (use-shares? state) (mesh-shares! state) (local-steps! state))
    (mark! state :faces)
    (let [triangles (make-triangles state)]
      (worked! state :untangle (* 0.3 geometry-work state.crossings))
      (mark! state :untangle)
      (untangle! state triangles)
      (worked! state :faces (* 0.3 geometry-work state.crossings))
      (mark! state nil)
      {:positions state.positions : triangles
       :stats {:points counts.points :blocks (length state.leaves) :skipped state.skipped
               :cells state.cell-count :crossings state.crossings
               :moved counts.moved :times state.times
               :flipped (or counts.flipped 0)
               :collections (or counts.collections 0)
               :untangled counts.untangled :crossing counts.crossing
               :shares (or counts.shares 1) :retaken (or counts.retaken 0)
               :work counts.work :estimate counts.estimate}})))

{: mesh : patches : box-distance : leaf :cut-field evaluator : settle-runs}

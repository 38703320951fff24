;; Grids over instance groups: culling for any node kind, trees included (a field's
;; members are lone primitives). An instance group (src/sdf/lower.fnl: many objects of
;; one structure, a loop over their rows) of at least `min-members` finite members gets
;; a uniform grid over their boxes; a cell lists the members whose box, grown by the
;; grid's reach, meets it. The group's code then runs for the members listed in the cell
;; of the point it is evaluated at, and the rest are stood in for by one lower bound:
;; the point's distance to its cell's walls plus the reach, or plus the cell's clearance
;; where that is more (the empty cells around it: see `clearances`). So the group's
;; value is exact within the reach of the point's cell and a lower bound beyond it,
;; never more than the true distance: a step never passes a surface. Any primitive, any
;; tree, rotated or not, is a member.
;;
;; The group's rows (its bank) go into a float texture, in coordinates relative to one
;; fixed anchor, so nothing is uploaded when the camera moves: the shader is sent the
;; anchor camera-relative and evaluates the members at p - anchor.
;;
;; Pure: runs under plain LuaJIT. The GLSL (shaders/pipeline/grid.glsl and
;; emit-glsl's grid loop) and the CPU reference (src/reference.fnl, through
;; `query`) read the same cells with the same arithmetic; brute force over every member
;; is the tests' oracle.

;; `pairs` under another name: a loop over `pairs` by that name is LuaJIT's ITERN,
;; which Debian 12's LuaJIT ends early once despecialised (see src/util/wire.fnl).
(local each-pair pairs)

(local floor math.floor)
(local min math.min)
(local max math.max)

;; From this many members on, an instance group gets a grid. Below it the loop over
;; every member costs less than the cells and the texture reads. Measured on llvmpipe
;; at 640x360 (rotated tori, capsules and boxes over a floor, one interleaved run):
;; 12 of each with grids 1.42x the time without, 20 of each 0.86x, 33 of each 0.21x.
(local min-members 16)

;; Cells per member: about this many cells in all per member. Lists grow as cells grow.
;; Measured on llvmpipe at 640x360 (one interleaved run each): 10,000 tori, capsules and
;; boxes 0.125: 1.86x the time of 2, 0.5: 1.16x; a smooth union of 10,000 spheres
;; (blend-cells-per-member) 0.5: 1.46x the time of 2, 1: 1.16x, 4: 0.92x, 8: 0.94x.
(local cells-per-member 2)
(local blend-cells-per-member 4)
(local max-cells-per-axis 256)

;; A member is listed in every cell its box comes within `reach` of: a quarter of the
;; smallest cell side. Sphere tracing near a wall steps at least the reach (less
;; reach, more steps to leave a cell), and soft shadows step by distance queries.
(local reach-fraction 0.25)

;; Texels per texture row, for an instance group's grid and a field's
;; (src/render/field.fnl) alike.
(local texture-width 1024)
(local max-texels (* 16384 texture-width))

(fn grid-dims [ex ey ez n per]
  "Cells along each axis for extents ex ey ez and n members: about per * n cubic
cells, at least one along each axis."
  (let [volume (* (max ex 1e-9) (max ey 1e-9) (max ez 1e-9))
        side (^ (/ volume (* per n)) (/ 1 3))
        dim (fn [e] (max 1 (min max-cells-per-axis (math.ceil (/ e side)))))]
    [(dim ex) (dim ey) (dim ez)]))

(fn clearances [[nx ny nz] counts]
  ;; Per cell (1-based), the Chebyshev distance in cells to the nearest cell other than
  ;; itself that lists something: 1 when a neighbour lists something, and so on; a
  ;; large number when none does. A breadth-first search over the 26 neighbours from
  ;; every listing cell gives each cell its distance to the nearest listing cell
  ;; (0 for one that lists); another cell's is then 1 + the least of its neighbours'.
  (let [cells (* nx ny nz)
        far (+ nx ny nz 1)
        dist (fcollect [k 1 cells] (if (> (. counts k) 0) 0 far))
        queue (icollect [k c (ipairs counts)] (when (> c 0) k))
        neighbours (fn [k visit]
                     (let [i (- k 1)
                           x (% i nx) y (% (floor (/ i nx)) ny) z (floor (/ i (* nx ny)))]
                       (for [dz -1 1] (for [dy -1 1] (for [dx -1 1]
                         (let [ax (+ x dx) ay (+ y dy) az (+ z dz)]
                           (when (and (not (and (= dx 0) (= dy 0) (= dz 0)))
                                      (>= ax 0) (< ax nx) (>= ay 0) (< ay ny) (>= az 0) (< az nz))
                             (visit (+ 1 ax (* nx (+ ay (* ny az))))))))))))]
    (var head 1)
    (while (<= head (length queue))
      (let [k (. queue head)
            next (+ 1 (. dist k))]
        (set head (+ head 1))
        (neighbours k (fn [j]
                        (when (> (. dist j) next)
                          (tset dist j next)
                          (table.insert queue j))))))
    (fcollect [k 1 cells]
      (if (> (. dist k) 0)
          (. dist k)
          (let [least [far]]
            (neighbours k (fn [j] (tset least 1 (min (. least 1) (. dist j)))))
            (min far (+ 1 (. least 1))))))))

(fn frame [boxes ?options]
  "The cells over the world boxes `boxes` ({:lo [x y z] :hi [x y z]}): about
cells-per-member (or the option :cells-per-member) a box, their box grown by the
reach. {:lo :dims [nx ny nz] :cell [sx sy sz] :size :reach :smallest (cell side)}.
Grids built on one frame share their walls, so a ray crosses one set of them."
  (let [options (or ?options {})
        n (length boxes)]
    (var (lx ly lz hx hy hz) (values math.huge math.huge math.huge (- math.huge) (- math.huge) (- math.huge)))
    (each [_ {: lo : hi} (ipairs boxes)]
      (set lx (min lx (. lo 1))) (set ly (min ly (. lo 2))) (set lz (min lz (. lo 3)))
      (set hx (max hx (. hi 1))) (set hy (max hy (. hi 2))) (set hz (max hz (. hi 3))))
    (let [[nx ny nz] (grid-dims (- hx lx) (- hy ly) (- hz lz) n
                                (or options.cells-per-member cells-per-member))
          smallest (min (/ (- hx lx) nx) (/ (- hy ly) ny) (/ (- hz lz) nz))
          smallest (if (> smallest 0) smallest 1e-3)
          reach (* reach-fraction smallest)
          size [(+ (- hx lx) (* 2 reach)) (+ (- hy ly) (* 2 reach)) (+ (- hz lz) (* 2 reach))]]
      {:lo [(- lx reach) (- ly reach) (- lz reach)] :dims [nx ny nz] : size : reach
       :cell [(/ (. size 1) nx) (/ (. size 2) ny) (/ (. size 3) nz)]
       :smallest (min (/ (. size 1) nx) (/ (. size 2) ny) (/ (. size 3) nz))})))

(fn build [boxes ?frame ?options]
  "The grid of the members whose world boxes are `boxes` ({:lo [x y z] :hi [x y z]},
in member order), on the cells `?frame` (see `frame`; by default their own). Option
:grow lists members that much further (a smooth union's blend radius). Returns
the frame's fields and :count, :start :count-of (per cell, 1-based; a list's first
slot 0-based), :clearance (per cell: the cells' skip, in world units) and :records
(member numbers, 0-based, per cell in order)."
  (let [{: lo : dims : cell : size : reach : smallest &as f} (or ?frame (frame boxes ?options))
        ;; A blend's children are listed a blend radius further (option :grow):
        ;; beyond it a child cannot change a smooth union's value.
        grow (+ reach (or (?. ?options :grow) 0))
        [nx ny nz] dims
        cells (* nx ny nz)
        count-of (fcollect [_ 1 cells] 0)
        ranges (icollect [_ {:lo blo :hi bhi} (ipairs boxes)]
                 (fcollect [a 1 3]
                   (let [d (. dims a)
                         s (. cell a)
                         o (. lo a)]
                     [(max 0 (min (- d 1) (floor (/ (- (. blo a) grow o) s))))
                      (max 0 (min (- d 1) (floor (/ (+ (. bhi a) grow (- o)) s))))])))
        visit (fn [r f]
                (let [[[x0 x1] [y0 y1] [z0 z1]] r]
                  (for [z z0 z1] (for [y y0 y1] (for [x x0 x1]
                    (f (+ 1 x (* nx (+ y (* ny z))))))))))
        _ (each [_ r (ipairs ranges)]
            (visit r #(tset count-of $ (+ 1 (. count-of $)))))
        start []
        fill []
        records []]
    (var at 0)
    (for [k 1 cells]
      (tset start k at)
      (tset fill k at)
      (set at (+ at (. count-of k))))
    (each [m r (ipairs ranges)]
      (visit r (fn [k]
                 (tset records (+ 1 (. fill k)) (- m 1))
                 (tset fill k (+ 1 (. fill k))))))
    (let [rings (clearances dims count-of)
          ;; (k - 1) cells of the smallest side past the point's own walls: no
          ;; listing cell nearer, so no member; at most the grid's diagonal.
          diagonal (math.sqrt (+ (^ (. size 1) 2) (^ (. size 2) 2) (^ (. size 3) 2)))]
      {:count (length boxes) : lo : dims : cell : size : reach : start : count-of : records
       ;; Each member's bounding sphere (world centre, radius), flat: a march skips a
       ;; member whose sphere it is far from by the ray's entry into it.
       :spheres (let [out []]
                  (each [_ {:lo [x0 y0 z0] :hi [x1 y1 z1]} (ipairs boxes)]
                    (each [_ v (ipairs [(* 0.5 (+ x0 x1)) (* 0.5 (+ y0 y1)) (* 0.5 (+ z0 z1))
                                        (* 0.5 (math.sqrt (+ (^ (- x1 x0) 2) (^ (- y1 y0) 2) (^ (- z1 z0) 2))))])]
                      (table.insert out v)))
                  out)
       :clearance (icollect [_ k (ipairs rings)] (min diagonal (* (- k 1) smallest)))})))

(local tiny 0.000001)

(fn slab-entry [qx qy qz sx sy sz dx dy dz]
  ;; Where the ray q + t d (q outside the box from 0 to s) enters the box, or nil when
  ;; it never does (gridCellAlong's slab test: tiny direction components replaced).
  (let [safe #(if (< (math.abs $) tiny) tiny $)
        ax (safe dx) ay (safe dy) az (safe dz)
        ta-x (/ (- qx) ax) tb-x (/ (- sx qx) ax)
        ta-y (/ (- qy) ay) tb-y (/ (- sy qy) ay)
        ta-z (/ (- qz) az) tb-z (/ (- sz qz) az)
        enter (max (min ta-x tb-x) (min ta-y tb-y) (min ta-z tb-z))
        leave (min (max ta-x tb-x) (max ta-y tb-y) (max ta-z tb-z))]
    (when (and (<= enter leave) (> leave 0)) enter)))

(fn query [g x y z ?dx ?dy ?dz ?far]
  "The cell of grid `g` at world point x y z: its list (first slot 0-based, count) and
the lower bound for every member it does not list, as the shader's gridCellAlong:
outside the grid, the distance to its box plus the reach; inside, the distance to the
cell's walls plus the reach or its clearance, whichever is more. With a ray direction
?dx ?dy ?dz (a unit vector), the bound is at least how far the ray may go before it
can meet an unlisted member: to the grid's box from outside (?far, the draw
distance, when it misses it), to the cell's far wall from inside."
  (let [[lx ly lz] g.lo
        [sx sy sz] g.size
        qx (- x lx) qy (- y ly) qz (- z lz)
        ox (max (- qx) (- qx sx) 0) oy (max (- qy) (- qy sy) 0) oz (max (- qz) (- qz sz) 0)
        along? (and ?dx (not (and (= ?dx 0) (= ?dy 0) (= ?dz 0))))]
    (if (> (max ox oy oz) 0)
        (let [bound (+ (math.sqrt (+ (* ox ox) (* oy oy) (* oz oz))) g.reach)]
          (values 0 0 (if along?
                          (max bound (or (slab-entry qx qy qz sx sy sz ?dx ?dy ?dz) ?far))
                          bound)))
        (let [[nx ny nz] g.dims
              [cx cy cz] g.cell
              ix (max 0 (min (- nx 1) (floor (/ qx cx))))
              iy (max 0 (min (- ny 1) (floor (/ qy cy))))
              iz (max 0 (min (- nz 1) (floor (/ qz cz))))
              k (+ 1 ix (* nx (+ iy (* ny iz))))
              wx (- qx (* ix cx)) wy (- qy (* iy cy)) wz (- qz (* iz cz))
              bound (+ (min wx (- cx wx) wy (- cy wy) wz (- cz wz))
                       (max g.reach (. g.clearance k)))
              ahead (fn [w c d] (/ (if (>= d 0) (- c w) w) (max (math.abs d) tiny)))]
          (values (. g.start k) (. g.count-of k)
                  (if along?
                      (max bound (min (ahead wx cx ?dx) (ahead wy cy ?dy) (ahead wz cz ?dz)))
                      bound))))))

(fn skip [g member x y z dx dy dz far]
  "How far a march along the unit vector dx dy dz from world point x y z may go before
it can meet member `member` (0-based) of grid `g` without evaluating it, or nil when
the point is within the grid's reach of the member's bounding sphere (gridSkip): its
entry into the sphere (`far` when it never enters), and at least its distance to it."
  (let [i (+ 1 (* 4 member))
        s g.spheres
        r (. s (+ i 3))
        ox (- x (. s i)) oy (- y (. s (+ i 1))) oz (- z (. s (+ i 2)))
        e (- (math.sqrt (+ (* ox ox) (* oy oy) (* oz oz))) r)]
    (when (> e g.reach)
      (let [b (+ (* ox dx) (* oy dy) (* oz dz))
            cx (- ox (* b dx)) cy (- oy (* b dy)) cz (- oz (* b dz))
            disc (- (* r r) (+ (* cx cx) (* cy cy) (* cz cz)))]
        (max e (if (or (< disc 0) (> b 0)) far (- (- b) (math.sqrt disc))))))))

(fn texture [texels data]
  "A texture of `texels` texels (texture-width a row, as many rows as they need),
its texels' numbers `data`."
  {:width texture-width :height (max 1 (math.ceil (/ texels texture-width))) : data})

(fn textures [grids bank-values [ax ay az] ?layouts]
  "The textures of a plan's grids and its instance bank: {:cells (per cell of every
grid in turn: first slot of its list, count, clearance, 0) :lists (member numbers, one
a texel) :spheres (per list slot, its member's bounding sphere: centre about the anchor
[ax ay az], radius) :firsts (per list slot, its member's first row in the bank, from
`?layouts`, each grid's {:base :stride}: a loop reads it without the member's number)
:bank (the rows `bank-values`, flat, 4 a row)} and :offsets (each grid's first cell
and list slot), or nil and a message when one would not fit."
  (let [cells []
        lists []
        spheres []
        firsts []
        offsets []]
    (var cell-at 0)
    (each [_ g (ipairs grids)]
      (let [list-at (/ (length lists) 4)]
        (table.insert offsets {:cell cell-at :list list-at})
        ;; A list slot's member's sphere at the same slot: a march reads it first and
        ;; the member's number only when it cannot skip the member (gridSkip).
        (each [_ m (ipairs g.records)]
          (let [s g.spheres
                i (+ 1 (* 4 m))]
            (each [_ v (ipairs [(- (. s i) ax) (- (. s (+ i 1)) ay) (- (. s (+ i 2)) az) (. s (+ i 3))])]
              (table.insert spheres v))))
        (let [{: base : stride} (or (?. ?layouts (length offsets)) {:base 0 :stride 0})]
          (each [_ m (ipairs g.records)]
            (let [at (* 4 (+ base (* m stride)))]
              (for [k 1 4] (table.insert firsts (or (. bank-values (+ at k)) 0))))))
        (each [k s (ipairs g.start)]
          (each [_ v (ipairs [(+ s list-at) (. g.count-of k) (. g.clearance k) 0])]
            (table.insert cells v)))
        (each [_ r (ipairs g.records)]
          (each [_ v (ipairs [r 0 0 0])] (table.insert lists v)))
        (set cell-at (+ cell-at (length g.start)))))
    (let [sizes {:cells cell-at :lists (/ (length lists) 4) :bank (/ (length bank-values) 4)
                 :spheres (/ (length spheres) 4) :firsts (/ (length firsts) 4)}
          over (accumulate [o nil name n (each-pair sizes)] (if (> n max-texels) name o))]
      (if over
          (values nil (string.format "the grids' %s need %d texels, more than a texture holds (%d)"
                                     over (. sizes over) max-texels))
          {:cells (texture cell-at cells) :lists (texture (. sizes :lists) lists)
           :spheres (texture sizes.spheres spheres)
           :firsts (texture sizes.firsts firsts)
           :bank (texture (. sizes :bank) bank-values) : offsets}))))

{: frame : build : query : skip : textures : min-members : blend-cells-per-member
 : texture-width : max-texels : grid-dims : texture}

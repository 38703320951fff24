;; Fields: the many small objects of a large scene, kept in float textures and found
;; through a uniform grid built here on the CPU so that a frame's cost stops growing
;; with the object count (uniform arrays marched every object every step). A ray walks
;; the grid's cells in order (a 3D DDA) and sphere-traces only the objects listed in the
;; cell it is in, so an empty cell costs one lookup and a full one a few objects,
;; whatever the scene's size. Pure: runs under plain LuaJIT. The shader
;; (shaders/pipeline/field.glsl and march.glsl's field walks) and the CPU reference
;; (src/reference.fnl) walk the same grid with the same arithmetic; brute force over
;; every object is the tests' oracle.
;;
;; The article's flat spheres and boxes are each a rounded box: centre c, half extents
;; h, radius r. A sphere is h = 0 (distance |p - c| - r, exact); a box is r = 0
;; (exact). One formula, no branch between them, and met along a ray in closed form.
;; Any other bounded primitive placed by translations and rotations alone
;; (lower.fnl's field-marched) is a marched member: its bounding sphere stands in for its box in the grid, and a ray
;; that enters that sphere sphere-traces the primitive's own distance in its frame
;; (marched-entry; fieldMarchedEntry in the shader), at most marched-turns steps.
;;
;; Coordinates are field-local (the grid's low corner is the origin), so the textures
;; do not change when the camera moves: the shader is sent the corner camera-relative,
;; computed in double.

;; `pairs` under another name: a loop over `pairs` by that name is LuaJIT's ITERN,
;; which Debian 12's LuaJIT ends early once despecialised (see src/util/wire.fnl).
(local each-pair pairs)

(local large-radius (. (require :src.sdf.large-sphere) :radius))
(local ffi (require :ffi))
(pcall ffi.cdef "void *calloc(size_t nmemb, size_t size); void free(void *ptr);")
(local lower (require :src.sdf.lower))
(local primitives (require :src.sdf.primitives))

(local sqrt math.sqrt)
(local floor math.floor)
(local min math.min)
(local max math.max)
(local abs math.abs)

;; From this many spheres and boxes on, a scene's spheres and boxes form a field.
;; Measured on llvmpipe at 640x360 (make bench's scaling scene, one interleaved run):
;; 10 spheres as a field 58 ms, in uniform arrays 57; 16: 70 against 86; 32: 72
;; against 201; 64: 82 against 358. (test/field_spec.fnl checks the switch, not the
;; speed.)
(local min-objects 16)

;; Textures and grid sizes as an instance group's grid has them (src/sdf/grid.fnl,
;; one grid system): every texture texture-width wide and as tall as it needs, at most
;; max-texels; llvmpipe allows 16384 x 16384, so the records texture (two texels a
;; record) holds at most this many records.
(local {: texture-width : max-texels : grid-dims : texture} (require :src.sdf.grid))
(local max-records (/ max-texels 2))

;; Grid cells per object (the grid's resolution): more cells mean shorter lists and
;; more cells to cross. Chosen on the scaling scenes of the benchmark at 640x360; for
;; a field of spheres (whose walk jumps across empty cells and skips a list whose
;; bound the ray misses) measured again with tools/scaling-ab.sh's dumps, one
;; interleaved run each: 1,000 spheres alike at 1, 2 and 4; 10,000 alike at 2, 4 and
;; 8; 100,000 173 ms at 2, 181 at 4, 188 at 8, 212 at 12.
(local cells-per-object 2)


;; An object is listed in every cell its box comes within `reach` of. The march needs
;; no reach (it never leaves a cell without crossing its wall), but a distance query
;; at a point sees exactly every object within `reach` of the point's cell (normals,
;; creases, adaptive edges, ambient occlusion) and a lower bound beyond: the walls
;; plus the reach. Longer reach, longer lists. A twentieth of the smallest cell side;
;; a quarter with soft shadows (their march steps by distance queries, and 128 steps
;; of at least the reach must cross the scene); at least the ambient occlusion radius
;; (up to one cell side).
(local reach-fraction 0.05)
(local wide-reach-fraction 0.25)
;; The walk of a field of spheres only (march.glsl's step-spheres) reads lists of its
;; own, grown by a hundredth of the smallest cell side: the walk meets an object in a
;; cell its surface is in, so it needs no reach but a margin for float rounding at
;; the walls (an entry computed just past a wall is still met). Shorter lists than
;; the distance queries' (a sphere of the benchmark's 10,000 in about 1.3 cells
;; instead of 1.6), and a list costs the walk a turn per sphere.
(local walk-reach-fraction 0.01)

(fn member? [o]
  "Whether object `o` can be part of a field: a flat sphere or box, or a marched
member (lower.fnl's field-marched), smaller than the large-sphere radius. (A
planet-sized sphere has its own cancellation-free code; and the field's coordinates
are relative to its grid's corner, not to the camera, so a giant box would stretch
the grid and cost small objects their float precision.)"
  (if o.tree
      (let [m (lower.field-marched o)]
        (and (not= nil m) (< m.radius large-radius)))
      (or (and (= o.kind :box)
               (let [[sx sy sz] o.size] (< (math.max sx sy sz) large-radius)))
          (and (= o.kind :sphere) (< o.radius large-radius)))))

(fn members [objects]
  "The objects of the list `objects` that go into a field, in order, or nil when
there are fewer than min-objects of them."
  (let [out (icollect [_ o (ipairs objects)] (when (member? o) o))]
    (when (>= (length out) min-objects) out)))

;; centre x y z, half extents x y z, radius: the round box the field draws.
(local shape lower.field-shape)

(fn shape-at [field i]
  "Object `i`'s (1-based) round box in the field: cx cy cz hx hy hz r, field-local
(seven doubles an object in :shapes, 56 MB for 1,000,000 where a table each took
130)."
  (let [s field.shapes
        at (* 7 (- i 1))]
    (values (. s at) (. s (+ at 1)) (. s (+ at 2)) (. s (+ at 3)) (. s (+ at 4))
            (. s (+ at 5)) (. s (+ at 6)))))

;; Steps a ray may take sphere-tracing one marched member, from where it enters its
;; bounding sphere; a ray still short of the hit test then misses it. (At most a few
;; on the benchmark's tori and capsules but along a grazing ray; 32 of the primitive's
;; distances cost less than one cell of the field.)
(local marched-turns 32)

;; Texels per object in the objects texture: centre and radius, half extents (or the
;; kind, negated) and number, colour; with marched members also their rotation (a
;; unit quaternion: one texel where its rows took three, measured 28 ms of 191 on
;; 10,000 tori, capsules and boxes) and their packed numbers, four to a texel
;; (arg-texels).
(fn arg-texels [field]
  "Texels of packed numbers per object (1 or 2) in the objects texture of a field
with marched members: as many as the kind with the most numbers needs."
  (accumulate [n 1 _ kind (ipairs field.kinds.marched)]
    (let [desc (primitives.lookup kind)
          numbers (accumulate [sum 0 _ a (ipairs desc.args)]
                    (+ sum (. primitives.glsl-types a.type)))]
      (max n (math.ceil (/ numbers 4))))))

(fn object-texels [field]
  "Texels per object in the field's objects texture."
  (if (> (length field.kinds.marched) 0) (+ 4 (arg-texels field)) 3))

(fn quaternion [[a b c d e f g h k]]
  "The unit quaternion x y z w that turns a vector as the rotation whose rows are
a b c, d e f, g h k does (v + 2 q x (q x v + w v), with q = x y z)."
  (let [trace (+ a e k)]
    (if (> trace 0)
        (let [s (/ 0.5 (sqrt (+ trace 1)))]
          (values (* (- h f) s) (* (- c g) s) (* (- d b) s) (/ 0.25 s)))
        (and (> a e) (> a k))
        (let [s (* 2 (sqrt (- (+ 1 a) e k)))]
          (values (* 0.25 s) (/ (+ b d) s) (/ (+ c g) s) (/ (- h f) s)))
        (> e k)
        (let [s (* 2 (sqrt (- (+ 1 e) a k)))]
          (values (/ (+ b d) s) (* 0.25 s) (/ (+ f h) s) (/ (- c g) s)))
        (let [s (* 2 (sqrt (- (+ 1 k) a e)))]
          (values (/ (+ c g) s) (/ (+ f h) s) (* 0.25 s) (/ (- d b) s))))))

(local round-box-cpu (. ((. (require :src.sdf.primitives) :lookup) :round-box) :cpu))

(fn rounded-box [qx qy qz cx cy cz hx hy hz r]
  ;; The shared distance, the round-box primitive's about centre c: a sphere when
  ;; h = 0, a box when r = 0; both exact.
  (round-box-cpu (- qx cx) (- qy cy) (- qz cz) hx hy hz r))

(fn list-cells [[nx ny nz] ranges n]
  ;; The cells' lists, laid out cell after cell, objects in each in scene order:
  ;; `ranges` gives the `n` objects' cells (see cover!: x0 x1 y0 y1 z0 z1, 0-based,
  ;; six to an object from 0). Returns {:start :count (per cell 1-based; a list's
  ;; first slot is 0-based) :records}. (Two passes over the same cells: written out
  ;; twice, as a closure made per object would keep LuaJIT from compiling the loop.)
  (let [cells (* nx ny nz)
        cell-count (fcollect [_ 1 cells] 0)
        cell-start []
        fill []
        records []]
    (for [i 1 n]
      (let [at (* 6 (- i 1))]
        (for [z (. ranges (+ at 4)) (. ranges (+ at 5))]
          (for [y (. ranges (+ at 2)) (. ranges (+ at 3))]
            (for [x (. ranges at) (. ranges (+ at 1))]
              (let [k (+ 1 x (* nx (+ y (* ny z))))]
                (tset cell-count k (+ (. cell-count k) 1))))))))
    (var at 0)
    (for [k 1 cells]
      (tset cell-start k at)
      (tset fill k at)
      (set at (+ at (. cell-count k))))
    (for [i 1 n]
      (let [at (* 6 (- i 1))]
        (for [z (. ranges (+ at 4)) (. ranges (+ at 5))]
          (for [y (. ranges (+ at 2)) (. ranges (+ at 3))]
            (for [x (. ranges at) (. ranges (+ at 1))]
              (let [k (+ 1 x (* nx (+ y (* ny z))))
                    slot (. fill k)]
                (tset records (+ slot 1) i)
                (tset fill k (+ slot 1))))))))
    {:start cell-start :count cell-count : records}))

(fn put-span! [ranges at c a r grow s d]
  ;; The cells from c - a - r - grow to c + a + r + grow along one axis (cells `s`
  ;; wide, `d` of them) into ranges[at] and ranges[at + 1].
  (tset ranges at (max 0 (min (- d 1) (floor (/ (- c a r grow) s)))))
  (tset ranges (+ at 1) (max 0 (min (- d 1) (floor (/ (+ c a r grow) s))))))

(fn cover! [ranges i cx cy cz ax ay az r [sx sy sz] [nx ny nz] grow]
  ;; Object `i`'s cells (its box, centre cx cy cz and half extents ax ay az grown by
  ;; r and `grow`; cells `s` wide, `n` to an axis) into `ranges` at 6 (i - 1):
  ;; x0 x1 y0 y1 z0 z1. An int32 array: six numbers an object (1,000,000 spheres'
  ;; two lists of ranges took 400 MB as tables).
  (let [at (* 6 (- i 1))]
    (put-span! ranges at cx ax r grow sx nx)
    (put-span! ranges (+ at 2) cy ay r grow sy ny)
    (put-span! ranges (+ at 4) cz az r grow sz nz)))

(fn lists [field ranges]
  ;; The field with its cells' lists (list-cells) as :cell-start :cell-count :records.
  (let [{: start : count : records} (list-cells field.dims ranges field.count)]
    (doto field
      (tset :cell-start start)
      (tset :cell-count count)
      (tset :records records))))

(local max-clearance 255)

(fn clearances [[nx ny nz] count]
  ;; Per cell, how far the walk may jump from it, for each octant of ray directions
  ;; o = (x < 0) + 2 (y < 0) + 4 (z < 0): 0 when the cell lists a sphere; else k >= 1
  ;; when the cube of k cells along each axis that has the cell at its corner and
  ;; goes on in the octant's directions is empty (cells past the grid's walls count
  ;; as empty), the largest such k up to max-clearance. A ray in that octant stays
  ;; in the cube until it leaves through one of the cube's far walls. By the
  ;; largest-cube recurrence, from the far corner back: 1 + the least of the seven
  ;; neighbours' toward the octant. Returned packed as an empty cell's texel holds
  ;; them: three lists (per cell, 1-based), octant o in list o // 3 + 1, 8 bits from
  ;; bit 8 (o % 3) (integers a float holds exactly).
  (let [cells (* nx ny nz)
        packed [(fcollect [_ 1 cells] 0) (fcollect [_ 1 cells] 0) (fcollect [_ 1 cells] 0)]
        k-of []
        plane (* nx ny)]
    (for [o 0 7]
      (let [sx (if (= 0 (% o 2)) 1 -1)
            sy (if (= 0 (% (floor (/ o 2)) 2)) 1 -1)
            sz (if (< o 4) 1 -1)
            out (. packed (+ 1 (floor (/ o 3))))
            weight (^ 256 (% o 3))
            dx sx dy (* sy nx) dz (* sz plane)]
        (for [zi 0 (- nz 1)]
          (let [z (if (> sz 0) (- nz 1 zi) zi)
                in-z? (< -1 (+ z sz) nz)]
            (for [yi 0 (- ny 1)]
              (let [y (if (> sy 0) (- ny 1 yi) yi)
                    in-y? (< -1 (+ y sy) ny)]
                (for [xi 0 (- nx 1)]
                  (let [x (if (> sx 0) (- nx 1 xi) xi)
                        in-x? (< -1 (+ x sx) nx)
                        k (+ 1 x (* nx y) (* plane z))
                        v (if (> (. count k) 0) 0
                              (let [far max-clearance
                                    a (if in-x? (. k-of (+ k dx)) far)
                                    b (if in-y? (. k-of (+ k dy)) far)
                                    c (if in-z? (. k-of (+ k dz)) far)
                                    ab (if (and in-x? in-y?) (. k-of (+ k dx dy)) far)
                                    ac (if (and in-x? in-z?) (. k-of (+ k dx dz)) far)
                                    bc (if (and in-y? in-z?) (. k-of (+ k dy dz)) far)
                                    abc (if (and in-x? in-y? in-z?) (. k-of (+ k dx dy dz)) far)]
                                (min max-clearance (+ 1 (min a b c ab ac bc abc)))))]
                    (tset k-of k v)
                    (tset out k (+ (. out k) (* v weight)))))))))))
    packed))

;; A list of this many spheres or more starts with the sphere about them (walk-texture):
;; a ray that misses it, or enters it past the cell, is done with the cell in one turn.
;; Measured on the benchmark's scaling scenes (tools/scaling-ab.sh's dumps, one
;; interleaved run): 100,000 spheres (in clusters along lines: cells list up to 20)
;; 34% faster with it from 3, 9% more from 2; 10,000 (mostly pairs) 7% faster from 2.
(local bound-from 2)

(fn with-walk [field walk-ranges]
  ;; A field of spheres only walks one texture of cells and lists (walk-texture)
  ;; when they fit in one: :walk (its lists, from `walk-ranges`), :walk? and :turns,
  ;; the walk's turns at most (a turn crosses a cell or meets a sphere of a list).
  (when (and (not field.kinds.boxes?) (= 0 (length field.kinds.marched)))
    (let [walk (list-cells field.dims walk-ranges field.count)
          cells (length walk.start)
          ;; (each list's texels: its spheres and, from bound-from on, the sphere
          ;; about them)
          texels (fn [n] (if (>= n bound-from) (+ n 1) n))
          listed (accumulate [sum 0 _ n (ipairs walk.count)] (+ sum (if (> n 1) (texels n) n)))
          longest (accumulate [m 0 _ n (ipairs walk.count)] (max m (texels n)))]
      (when (<= (+ cells listed) max-texels)
        (set field.walk walk)
        (set field.walk? true)
        (set field.turns (+ field.crossings (min listed (* field.crossings longest)))))))
  field)

(fn build [objects ?options]
  "The field of `objects` (members, in order): the grid and the texture data.
Options: :reach-at-least (a distance queries must see exactly, e.g. the ambient
occlusion radius), :wide? (soft shadows: a quarter cell's reach), :cells-per-object
(the grid's resolution; the benchmark's). Returns {:count :objects :lo [x y z] (world) :dims [nx ny nz]
:cell [sx sy sz] :size [x y z] :reach :crossings (cells a ray can cross, at most)
:cell-start :cell-count (per cell, 0-based) :records (object numbers, 1-based, per
cell in order) :shapes (seven doubles an object, see shape-at: cx cy cz hx hy hz r, field-local; a marched
member's bounding sphere) :colors :kinds (lower.fnl's field-kinds) :marched (per
marched member: {:kind (its number, from 1) :desc :args :rows})
:textures (made on first use: see textures)}; or nil and a message when the grid's
lists would not fit in a texture."
  (let [options (or ?options {})
        n (length objects)
        shapes (ffi.new "double[?]" (* 7 n))]
    ;; Bounding box of every object's box.
    (var (lx ly lz hx hy hz) (values math.huge math.huge math.huge (- math.huge) (- math.huge) (- math.huge)))
    (each [_ o (ipairs objects)]
      (let [(cx cy cz ax ay az r) (shape o)]
        (set lx (min lx (- cx ax r))) (set ly (min ly (- cy ay r))) (set lz (min lz (- cz az r)))
        (set hx (max hx (+ cx ax r))) (set hy (max hy (+ cy ay r))) (set hz (max hz (+ cz az r)))))
    (let [[nx ny nz] (grid-dims (- hx lx) (- hy ly) (- hz lz) n
                                (or options.cells-per-object cells-per-object))
          smallest (min (/ (- hx lx) nx) (/ (- hy ly) ny) (/ (- hz lz) nz))
          smallest (if (> smallest 0) smallest 1e-3)
          fraction (if options.wide? wide-reach-fraction reach-fraction)
          reach (min smallest (max (* fraction smallest) (or options.reach-at-least 0)))
          ;; The grid holds every object's box grown by the reach.
          lo [(- lx reach) (- ly reach) (- lz reach)]
          size [(+ (- hx lx) (* 2 reach)) (+ (- hy ly) (* 2 reach)) (+ (- hz lz) (* 2 reach))]
          cell [(/ (. size 1) nx) (/ (. size 2) ny) (/ (. size 3) nz)]
          [ox oy oz] lo
          [sx sy sz] cell
          walk-reach (min reach (* walk-reach-fraction smallest))
          ranges (ffi.new "int32_t[?]" (* 6 n))
          walk-ranges (ffi.new "int32_t[?]" (* 6 n))
          colors []
          ;; Which kinds it holds (only their code is compiled in), and per marched
          ;; member its kind's number (from 1), primitive, numbers and rotation.
          kinds (lower.field-kinds objects)
          kind-number (collect [k name (ipairs kinds.marched)] name k)
          marched {}]
      ;; Shapes in field-local coordinates, and the cells each object's grown box
      ;; covers.
      (each [i o (ipairs objects)]
        (let [(cx cy cz ax ay az r) (shape o)
              cx (- cx ox) cy (- cy oy) cz (- cz oz)]
          (let [at (* 7 (- i 1))]
            (tset shapes at cx) (tset shapes (+ at 1) cy) (tset shapes (+ at 2) cz)
            (tset shapes (+ at 3) ax) (tset shapes (+ at 4) ay) (tset shapes (+ at 5) az)
            (tset shapes (+ at 6) r))
          (if o.tree
              (let [{: desc : args : rows : color} (lower.field-marched o)]
                (tset marched i {:kind (. kind-number desc.kind) : desc : args : rows})
                (tset colors i color))
              (tset colors i o.color))
          (cover! ranges i cx cy cz ax ay az r cell [nx ny nz] reach)
          (cover! walk-ranges i cx cy cz ax ay az r cell [nx ny nz] walk-reach)))
      ;; Every object is listed in each cell it covers: a texture holds at most
      ;; max-records of those (two texels each).
      (let [total (faccumulate [sum 0 i 0 (- n 1)]
                    (let [at (* 6 i)]
                      (+ sum (* (+ 1 (- (. ranges (+ at 1)) (. ranges at)))
                                (+ 1 (- (. ranges (+ at 3)) (. ranges (+ at 2))))
                                (+ 1 (- (. ranges (+ at 5)) (. ranges (+ at 4))))))))]
        (if (> total max-records)
            (values nil (string.format (.. "objects: the field's grid lists its %d spheres and boxes %d times"
                                           " (each in every cell it covers), more than the %d a texture"
                                           " holds; remove or shrink the largest ones")
                                       n total max-records))
            (with-walk (lists {:count n : objects : lo :dims [nx ny nz] : cell : size : reach
                    ;; Which kinds it holds: only their code is compiled in.
                    : kinds
                    :crossings (+ nx ny nz 1)
                    : shapes : colors : marched}
                   ranges)
                       walk-ranges))))))

(local tiny-radius 1e-30)

;; A field of this many objects or more, without functions of time, may let its
;; textures' floats go once uploaded (release-floats!).
(local release-from 100000)

(fn float-texture [texels count]
  ;; A texture of `texels` RGBA texels whose first `count` floats are written next:
  ;; {:width :height :floats (float[4 * width * height], 0-based, the rest 0) :count}.
  ;; float32, as the GPU reads them (1,000,000 spheres' textures took 518 MB as Lua
  ;; numbers, tables of doubles grown by doubling).
  ;; Their memory is C's (calloc, freed by the collector or at once by
  ;; release-floats!): LuaJIT's own would wait for a collection to go, and a large
  ;; field's textures are let go just when the scene's memory peaks.
  (let [t (texture texels nil)
        n (* 4 t.width t.height)]
    (set t.floats (ffi.gc (ffi.cast "float *" (assert (ffi.C.calloc n 4) "field: out of memory for a texture"))
                          ffi.C.free))
    (set t.count count)
    t))

(fn walk-texture [field]
  ;; A field of spheres only: the texture its walk reads (march.glsl's step-spheres),
  ;; the cells then every list, a texel each. A cell listing one sphere holds it
  ;; (centre, radius; when the radius is over tiny-radius, so that it stays above 0
  ;; in float); a cell listing more holds where its list starts in this texture,
  ;; its length, 0 and -1; an empty cell its clearances (how many cells on the walk
  ;; may jump, per octant of directions: clearances) and 0. A record is its sphere's
  ;; centre and radius; a list of bound-from or more starts with the sphere about
  ;; its spheres, radius negated. The walk then reads one texel per cell it crosses
  ;; that lists a sphere, one per sphere in a cell that lists several (but one for
  ;; all when the ray misses the sphere about them), and one per jump across empty
  ;; cells.
  (let [{: start : count : records} field.walk
        cells (length start)
        ;; Its size: the cells, then each list of two or more (its sphere about them
        ;; first when it has bound-from or more).
        one? (fn [k] (and (= (. count k) 1)
                          (> (select 7 (shape-at field (. records (+ (. start k) 1)))) tiny-radius)))
        texels (accumulate [n cells k c (ipairs count)]
                 (+ n (if (or (= c 0) (one? k)) 0 (>= c bound-from) (+ c 1) c)))
        tex (float-texture texels (* 4 texels))
        walk tex.floats
        clear (clearances field.dims count)
        put (fn [texel a b c d]
              (let [at (* 4 texel)]
                (tset walk at a) (tset walk (+ at 1) b)
                (tset walk (+ at 2) c) (tset walk (+ at 3) d)))]
    ;; The cells, then the lists in their cells' order. A list's sphere about its
    ;; spheres: centre the mean of theirs, radius the farthest one's reach from it,
    ;; grown by a ten-thousandth of that and of the centre's distance from the
    ;; grid's corner, so that it holds them still with everything rounded to float.
    (var at cells)
    (for [k 1 cells]
      (let [first (. start k)
            n (. count k)]
        (if (= n 0) (put (- k 1) (. clear 1 k) (. clear 2 k) (. clear 3 k) 0)
            (one? k)
            (let [(cx cy cz _ _ _ r) (shape-at field (. records (+ first 1)))]
              (put (- k 1) cx cy cz r))
            ;; (The spheres by number: a table of each one's values, {(shape-at ...)},
            ;; is a bytecode LuaJIT does not compile, and this loop ran 70 times slower.)
            (let [listed (fcollect [j 1 n] (. records (+ first j)))
                  bounded? (>= n bound-from)]
              (put (- k 1) at (if bounded? (+ n 1) n) 0 -1)
              (when bounded?
                (var (mx my mz) (values 0 0 0))
                (each [_ i (ipairs listed)]
                  (let [(cx cy cz) (shape-at field i)]
                    (set (mx my mz) (values (+ mx (/ cx n)) (+ my (/ cy n)) (+ mz (/ cz n))))))
                (let [reach (accumulate [m 0 _ i (ipairs listed)]
                              (let [(cx cy cz _ _ _ r) (shape-at field i)]
                                (max m (+ r (sqrt (+ (* (- cx mx) (- cx mx)) (* (- cy my) (- cy my))
                                                     (* (- cz mz) (- cz mz))))))))]
                  (put at mx my mz (- (+ reach (* 1e-4 (+ reach (max (abs mx) (abs my) (abs mz)))))))
                  (set at (+ at 1))))
              (each [_ i (ipairs listed)]
                (let [(cx cy cz _ _ _ r) (shape-at field i)]
                  (put at cx cy cz r))
                (set at (+ at 1)))))))
    (assert (= at texels) "field: the walk texture's size")
    tex))

(fn make-textures [field]
  ;; The textures of `field` (see textures), made anew.
  (let [stride (object-texels field)
        cells-tex (float-texture (length field.cell-start) (* 4 (length field.cell-start)))
        records-tex (float-texture (* 2 (length field.records)) (* 8 (length field.records)))
        objects-tex (float-texture (* stride field.count) (* 4 stride field.count))
        cells cells-tex.floats
        records records-tex.floats
        objects objects-tex.floats]
    (each [k start (ipairs field.cell-start)]
      (let [at (* 4 (- k 1))]
        (tset cells at start)
        (tset cells (+ at 1) (. field.cell-count k))))
    (each [j i (ipairs field.records)]
      (let [(cx cy cz ax ay az r) (shape-at field i)
            m (. field.marched i)
            at (* 8 (- j 1))]
        (tset records at cx) (tset records (+ at 1) cy) (tset records (+ at 2) cz)
        (tset records (+ at 3) r)
        (tset records (+ at 4) (if m (- m.kind) ax)) (tset records (+ at 5) ay)
        (tset records (+ at 6) az)
        (tset records (+ at 7) (- i 1))))
    (for [i 1 field.count]
      (let [(cx cy cz ax ay az r) (shape-at field i)
            [cr cg cb] (. field.colors i)
            m (. field.marched i)
            at (* 4 stride (- i 1))]
        (tset objects at cx) (tset objects (+ at 1) cy) (tset objects (+ at 2) cz)
        (tset objects (+ at 3) r) (tset objects (+ at 4) (if m (- m.kind) ax))
        (tset objects (+ at 5) ay) (tset objects (+ at 6) az) (tset objects (+ at 7) (- i 1))
        (tset objects (+ at 8) cr) (tset objects (+ at 9) cg) (tset objects (+ at 10) cb)
        (when (> stride 3)
          (let [(qx qy qz qw) (quaternion (if m m.rows [1 0 0 0 1 0 0 0 1]))
                args (if m m.args [])]
            (tset objects (+ at 12) qx) (tset objects (+ at 13) qy)
            (tset objects (+ at 14) qz) (tset objects (+ at 15) qw)
            (for [j 1 (* 4 (- stride 4))]
              (tset objects (+ at 15 j) (or (. args j) 0)))))))
    {:cells cells-tex :records records-tex :objects objects-tex
     :walk (when field.walk? (walk-texture field))}))

(fn textures [field]
  "The field's float textures (made once, then kept in the field):
  :cells    one texel per cell: first record, record count
  :walk     a field of spheres only: the cells and lists as its walk reads
            them, a texel each (see walk-texture); nil for other fields
  :records  two texels per record: centre and radius, half extents and the
            object's number (0-based); a marched member's bounding sphere, its
            kind's number negated (then 0, 0) and its number
  :objects  per object (object-texels): its record's two texels, its colour;
            with marched members also a marched member's rotation (quaternion)
            and its packed numbers (arg-texels)
Each {:width :height} and its floats row after row, float32 in :floats (see
float-texture, texture-values)."
  (when (not field.textures)
    (set field.textures (make-textures field))
    (each [_ t (each-pair field.textures)]
      ;; A texture of a large field without functions of time may let its floats
      ;; go once a backend has its own copy (release-floats!); floats-of makes
      ;; them again.
      (set t.field field)
      (set t.release? (and field.static? (>= field.count release-from)))))
  field.textures)

(fn release-floats! [tex]
  "Let the floats of texture `tex` (a field's, see textures) go when its :release?
says it may (a large field without functions of time, whose texture a backend has
copied): 150 MB for 1,000,000 spheres, held a third time beside LÖVE's copy and the
driver's. floats-of makes them again when something reads them."
  (when (and tex.release? tex.floats)
    (ffi.C.free (ffi.gc tex.floats nil))
    (set tex.floats nil)))

(fn floats-of [tex]
  "The float32 :floats of field texture `tex`, made again (into the tables a backend
knows, which key its images) if release-floats! let them go."
  (when (and (= nil tex.floats) tex.field)
    (each [k t (each-pair (make-textures tex.field))]
      (set (. tex.field.textures k :floats) t.floats)))
  tex.floats)

(fn texture-values [tex]
  "The floats of texture `tex` as a list (1-based): its :data, or the first :count of
its :floats."
  (or tex.data (let [floats (floats-of tex)] (fcollect [i 0 (- tex.count 1)] (. floats i)))))

;;; Queries (the CPU side of shaders/pipeline/field.glsl), in world coordinates.

(local unpack (or table.unpack _G.unpack))

(fn marched-distance [m qx qy qz cx cy cz]
  "fieldMarchedDistance: marched member `m` (lower.fnl's field-marched, about its
origin c) at q, in its frame."
  (let [[a b c d e f g h k] m.rows
        x (- qx cx) y (- qy cy) z (- qz cz)]
    (m.desc.cpu (+ (* a x) (* b y) (* c z)) (+ (* d x) (* e y) (* f z)) (+ (* g x) (* h y) (* k z))
                (unpack m.args))))

(fn member-distance [field i qx qy qz]
  "fieldMemberDistance: the field's object `i` (1-based) at field-local (qx qy qz)."
  (let [(cx cy cz ax ay az r) (shape-at field i)
        m (. field.marched i)]
    (if m (marched-distance m qx qy qz cx cy cz)
        (rounded-box qx qy qz cx cy cz ax ay az r))))

(fn object-distance [field i x y z]
  "Distance from world point (x y z) to the field's object `i` (1-based)."
  (let [[ox oy oz] field.lo]
    (member-distance field i (- x ox) (- y oy) (- z oz))))

(fn cell-distance [field k qx qy qz ?skip]
  "Nearest listed object of cell `k` (1-based) to field-local (qx qy qz), skipping
object `?skip`: distance (math.huge when none) and object number (or nil). Ties go
to the earlier record."
  (let [records field.records
        start (. field.cell-start k)]
    (var d math.huge)
    (var best nil)
    (for [j (+ start 1) (+ start (. field.cell-count k))]
      (let [i (. records j)]
        (when (not= i ?skip)
          (let [di (member-distance field i qx qy qz)]
            (when (< di d) (set d di) (set best i))))))
    (values d best)))

;; A ray direction's components smaller than this are replaced by it (kFieldTiny),
;; so a reciprocal is huge, not an infinity, along an axis the ray does not move on.
(local tiny 0.000001)

(fn safe-component [v]
  (if (< (abs v) tiny) tiny v))

(fn reciprocal [dx dy dz]
  "The reciprocal of the ray direction (dx dy dz) with tiny components replaced, as
the shader's fieldSafeDirection: ix iy iz (their signs are the walk's steps)."
  (values (/ 1 (safe-component dx)) (/ 1 (safe-component dy)) (/ 1 (safe-component dz))))

(fn entry [qx qy qz dx dy dz ix iy iz cx cy cz ax ay az r far]
  ;; fieldEntry: where the ray q + t d first enters the object, at t >= 0, or `far`.
  ;; (ix iy iz: the reciprocal of d, tiny components replaced as the shader does.)
  (if (> r 0)
      (let [ox (- qx cx) oy (- qy cy) oz (- qz cz)
            b (+ (* ox dx) (* oy dy) (* oz dz))
            px (- ox (* b dx)) py (- oy (* b dy)) pz (- oz (* b dz))
            disc (- (* r r) (+ (* px px) (* py py) (* pz pz)))]
        (if (< disc 0) far
            (let [s (sqrt disc)]
              (if (< (- s b) 0) far (max (- (- b) s) 0)))))
      (let [x1 (* (- cx ax qx) ix) x2 (* (- (+ cx ax) qx) ix)
            y1 (* (- cy ay qy) iy) y2 (* (- (+ cy ay) qy) iy)
            z1 (* (- cz az qz) iz) z2 (* (- (+ cz az) qz) iz)
            near (max (min x1 x2) (min y1 y2) (min z1 z2))
            far* (min (max x1 x2) (max y1 y2) (max z1 z2))]
        (if (or (> near far*) (< far* 0)) far (max near 0)))))

(fn marched-entry [field i qx qy qz dx dy dz far hit]
  "fieldMarchedEntry: where the ray (field-local origin q, unit direction d) first
meets marched member `i` (1-based), or `far`: from where it enters the member's
bounding sphere (at t >= 0), the member's distance sphere-traced in its frame until
a step is under the hit test, at most marched-turns steps and no farther than the
sphere's exit. `hit` gives the hit test: {:t0 (the distance travelled to q)
:threshold (fn [distance from the camera]) :start-limit (fn [d at the ray's
start])}, a march's: a secondary ray's own start is no hit."
  (let [(cx cy cz _ _ _ r) (shape-at field i)
        m (. field.marched i)
        ox (- qx cx) oy (- qy cy) oz (- qz cz)
        b (+ (* ox dx) (* oy dy) (* oz dz))
        px (- ox (* b dx)) py (- oy (* b dy)) pz (- oz (* b dz))
        disc (- (* r r) (+ (* px px) (* py py) (* pz pz)))
        s (sqrt (max disc 0))
        t-out (- s b)]
    (if (or (< disc 0) (< t-out 0)) far
        (let [[ra rb rc rd re rf rg rh rk] m.rows
              cpu m.desc.cpu
              args m.args
              ;; The ray in the member's frame.
              lx (+ (* ra ox) (* rb oy) (* rc oz)) ly (+ (* rd ox) (* re oy) (* rf oz))
              lz (+ (* rg ox) (* rh oy) (* rk oz))
              ux (+ (* ra dx) (* rb dy) (* rc dz)) uy (+ (* rd dx) (* re dy) (* rf dz))
              uz (+ (* rg dx) (* rh dy) (* rk dz))
              t0 hit.t0]
          (var t (max (- (- b) s) 0))
          (var limit math.huge)
          (var result nil)
          (for [turn 1 marched-turns &until result]
            (let [d (cpu (+ lx (* ux t)) (+ ly (* uy t)) (+ lz (* uz t)) (unpack args))]
              (when (and (= turn 1) (= t 0) (> t0 0)) (set limit (hit.start-limit d)))
              (if (< d (min (hit.threshold (+ t0 t)) limit)) (set result t)
                  (do (set t (+ t d))
                      (when (> t t-out) (set result far))))))
          (or result far)))))

(fn list-entry [field k qx qy qz dx dy dz ix iy iz far ?lists ?hit]
  "fieldListEntry: where the ray (field-local origin q, unit direction d, reciprocal
i) first enters an object listed in cell `k` (1-based), or `far`. The lists are
the field's, or `?lists` ({:start :count :records}, the walk's). `?hit`, a
march's hit test (see marched-entry), is needed when the field has marched members."
  (let [marched field.marched
        records (if ?lists ?lists.records field.records)
        start (. (if ?lists ?lists.start field.cell-start) k)
        count (. (if ?lists ?lists.count field.cell-count) k)]
    (var t far)
    (for [j (+ start 1) (+ start count)]
      (let [i (. records j)]
        (set t (min t (if (. marched i)
                          (marched-entry field i qx qy qz dx dy dz far ?hit)
                          (let [(cx cy cz ax ay az r) (shape-at field i)]
                            (entry qx qy qz dx dy dz ix iy iz cx cy cz ax ay az r far)))))))
    t))

(fn cell-along [q s n]
  ;; The cell (0-based) holding coordinate q on an axis of n cells of side s, clamped.
  (max 0 (min (- n 1) (floor (/ q s)))))

(fn cell-of [field qx qy qz]
  "The cell holding field-local (qx qy qz), clamped into the grid: x y z (0-based)
and its number k (1-based)."
  ;; (No closure here: LuaJIT compiles no function that makes one, and this runs for
  ;; every point the CPU reference or a mesh reads in a field.)
  (let [[nx ny nz] field.dims
        [sx sy sz] field.cell
        x (cell-along qx sx nx) y (cell-along qy sy ny) z (cell-along qz sz nz)]
    (values x y z (+ 1 x (* nx (+ y (* ny z)))))))

(fn distance [field x y z ?skip]
  "The field's distance at world (x y z) as the shader's fieldMap gives it: exact
within the reach of the point's cell, a lower bound beyond (the cell's walls plus
the reach). Returns the distance and the nearest listed object (1-based, or nil)."
  (let [[ox oy oz] field.lo
        [wx wy wz] field.size
        qx (- x ox) qy (- y oy) qz (- z oz)
        outx (max (- qx) (- qx wx) 0)
        outy (max (- qy) (- qy wy) 0)
        outz (max (- qz) (- qz wz) 0)]
    (if (> (max outx outy outz) 0)
        ;; Outside the grid: every object is at least the reach inside it.
        (values (+ (sqrt (+ (* outx outx) (* outy outy) (* outz outz))) field.reach) nil)
        (let [(cx cy cz k) (cell-of field qx qy qz)
              [sx sy sz] field.cell
              wall (+ field.reach
                      (min (- qx (* cx sx)) (- (* (+ cx 1) sx) qx)
                           (- qy (* cy sy)) (- (* (+ cy 1) sy) qy)
                           (- qz (* cz sz)) (- (* (+ cz 1) sz) qz)))
              (d best) (cell-distance field k qx qy qz ?skip)]
          (values (min d wall) best)))))

(fn brute-distance [field x y z ?skip]
  "The test oracle: the exact distance over every object of the field, and the
nearest object (ties to the earlier)."
  (var d math.huge)
  (var best nil)
  (for [i 1 field.count]
    (when (not= i ?skip)
      (let [di (object-distance field i x y z)]
        (when (< di d) (set d di) (set best i)))))
  (values d best))

(fn float-reader [tex]
  ;; A texture's floats, 1-based, and how many: from :data or :floats (nil when
  ;; they were let go: release-floats!).
  (if (and (= nil tex.data) (= nil tex.floats)) nil
      tex.floats
      (let [f tex.floats] (values (fn [i] (. f (- i 1))) tex.count))
      (let [d tex.data] (values (fn [i] (. d i)) (length d)))))

(fn changed-spans [old new]
  "Where two textures of one width differ (`old` and `new`, {:width} and their floats,
see textures): a list of [row first-texel last-texel] (0-based), one per row that
changed, from its first changed texel to its last; nil when their sizes or widths
differ (the texture is new). A value edit then uploads only the texels it touched."
  (let [(old-at old-n) (float-reader old)
        (new-at n) (float-reader new)]
    (when (and old-at new-at (= old-n n) (= old.width new.width))
      (let [out []
            per-row (* 4 new.width)]
        (for [row 0 (- (math.ceil (/ n per-row)) 1)]
          (var first nil)
          (var last nil)
          (let [base (* row per-row)]
            (for [i (+ base 1) (math.min n (+ base per-row))]
              (when (not= (old-at i) (new-at i))
                (let [texel (math.floor (/ (- i base 1) 4))]
                  (when (not first) (set first texel))
                  (set last texel)))))
          (when first (table.insert out [row first last])))
        out))))

(fn walk [field ox oy oz dx dy dz t-past max-steps]
  "The walk of a field of spheres only (march.glsl's step-spheres) on the CPU,
reading the walk texture as the shader does (its cells' spheres, lists and
clearances) with the same steps: where the ray
from world (ox oy oz) along the unit vector (dx dy dz) first enters a sphere of a
field of spheres only (field.walk?) before `t-past` (the nearest plane or the
ray's end), else `t-past`; with the cells it met that list something (the
shader's steps). After `max-steps` of those: :out and where it stopped."
  (let [data (floats-of (. (textures field) :walk))
        ;; Where the ray's octant's clearance is in an empty cell's texel.
        octant (let [(ix iy iz) (reciprocal dx dy dz)]
                 (+ (if (< ix 0) 1 0) (if (< iy 0) 2 0) (if (< iz 0) 4 0)))
        channel (+ 1 (floor (/ octant 3)))
        scale (^ 256 (- (% octant 3)))
        ;; float32, as the shader reads them.
        texel (fn [i] (let [at (* 4 i)]
                        (values (. data at) (. data (+ at 1)) (. data (+ at 2)) (. data (+ at 3)))))
        [lx ly lz] field.lo
        [wx wy wz] field.size
        [sx sy sz] field.cell
        [nx ny nz] field.dims
        qx (- ox lx) qy (- oy ly) qz (- oz lz)
        (ix iy iz) (reciprocal dx dy dz)
        near (fn [q w i] (min (* (- q) i) (* (- w q) i)))
        far (fn [q w i] (max (* (- q) i) (* (- w q) i)))
        grid-in (max (near qx wx ix) (near qy wy iy) (near qz wz iz) 0)
        t-end (min (far qx wx ix) (far qy wy iy) (far qz wz iz) t-past)]
    (if (>= grid-in t-end) (values t-past 0)
        (let [c (fn [q s n] (max 0 (min (- n 1) (floor (/ q s)))))
              cx (c (+ qx (* dx grid-in)) sx nx)
              cy (c (+ qy (* dy grid-in)) sy ny)
              cz (c (+ qz (* dz grid-in)) sz nz)
              up (fn [i] (if (> i 0) 1 0))
              delta [(* sx (abs ix)) (* sy (abs iy)) (* sz (abs iz))]
              stride [(if (> ix 0) 1 -1) (if (> iy 0) nx (- nx)) (if (> iz 0) (* nx ny) (- (* nx ny)))]
              t-next [(* (- (* (+ cx (up ix)) sx) qx) ix)
                      (* (- (* (+ cy (up iy)) sy) qy) iy)
                      (* (- (* (+ cz (up iz)) sz) qz) iz)]]
          (var index (+ cx (* nx (+ cy (* ny cz)))))
          (var next 0)
          (var left 0)
          (var hit math.huge)
          (var steps 0)
          (var result nil)
          (var stop grid-in)
          (for [_ 0 field.turns &until result]
            (let [in-list? (> left 0)
                  (x y z w) (texel (if in-list? next index))]
              ;; A list's first texel may be the sphere about its spheres (radius
              ;; negated): entered past the cell or not at all, none is the hit.
              (let [bound? (and in-list? (< w 0))
                    e (when (or in-list? (> w 0))
                        (entry qx qy qz dx dy dz ix iy iz x y z 0 0 0 (abs w) math.huge))
                    past? (and bound? (> e (min (. t-next 1) (. t-next 2) (. t-next 3))))
                    starts? (and (not in-list?) (< w 0))]
                (when (and e (not bound?)) (set hit (min hit e)))
                (set next (if starts? x (+ next 1)))
                (set left (if starts? y past? 0 (max (- left 1) 0))))
              (when (and (not in-list?) (not= w 0)) (set steps (+ steps 1)))
              (when (= left 0)
                ;; From an empty cell of clearance k in the ray's octant: past the
                ;; empty cube of k cells on from it.
                (let [packed (floor (* (. [x y z] channel) scale))
                      k (- packed (* 256 (floor (/ packed 256))))
                      reach (if (and (not in-list?) (= w 0)) (max (- k 1) 0) 0)
                      cell-end (accumulate [m math.huge a tn (ipairs t-next)]
                                 (min m (+ tn (* reach (. delta a)))))]
                  (if (and (<= hit cell-end) (< hit t-end)) (set result hit)
                      (>= cell-end t-end) (set result t-past)
                      (>= steps max-steps) (do (set stop (max stop cell-end))
                                               (set result :out))
                      (do
                        (for [a 1 3]
                          (let [m (max 0 (min (+ reach 1)
                                              (+ 1 (floor (/ (- cell-end (. t-next a)) (. delta a))))))]
                            (tset t-next a (+ (. t-next a) (* m (. delta a))))
                            (set index (+ index (* m (. stride a))))))
                        (set hit math.huge)
                        ;; (out of the grid where its far wall rounds to before t-end)
                        (when (or (< index 0) (>= index (* nx ny nz)))
                          (set result t-past))))))))
          ;; Out of steps or turns: the shader's out-of-steps slot.
          (if (and result (not= result :out)) (values result steps)
              (values :out steps stop))))))

(fn brute-entry [field ox oy oz dx dy dz far ?hit]
  "The test oracle of the walk: where the ray from world (ox oy oz) along the unit
vector (dx dy dz) first enters any object of the field, in closed form (a marched
member's by marched-entry, with the hit test `?hit`), or `far`."
  (let [[lx ly lz] field.lo
        qx (- ox lx) qy (- oy ly) qz (- oz lz)
        (ix iy iz) (reciprocal dx dy dz)]
    (var t far)
    (for [i 1 field.count]
      (set t (min t (if (. field.marched i)
                        (marched-entry field i qx qy qz dx dy dz far ?hit)
                        (let [(cx cy cz ax ay az r) (shape-at field i)]
                          (entry qx qy qz dx dy dz ix iy iz cx cy cz ax ay az r far))))))
    t))

{: member? : members : brute-entry : marched-entry : marched-turns : object-texels
 : arg-texels : quaternion
 : member-distance : walk : reciprocal : tiny : changed-spans : build : textures : release-floats! : floats-of : object-distance : cell-distance : cell-of : list-entry
 : distance : brute-distance : rounded-box : min-objects : texture-width : texture-values : shape-at
 : marched-distance}

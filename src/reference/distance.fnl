;; The CPU reference's distance field: the tape's objects folded as the shader folds
;; them (map, mapFinite, mapColor, mapObject and planesHit), each tape object's run
;; of objects through its drawing strategy's queries (src/sdf/strategies/).

(local grid (require :src.sdf.grid))
(local strategies (require :src.sdf.strategies))

(fn half-spaces [plan]
  "Whether each tape object (by tape number) is a half-space, met in closed form with
bounds."
  (let [out {}]
    (var j 0)
    (each [_ o (ipairs (strategies.queried plan.tape))]
      (for [_ 1 (strategies.count o)]
        (set j (+ j 1))
        (tset out j o.half-space?)))
    out))

(fn runs [plan]
  "The tape's objects as the shader folds them, run by run: {:first :last (numbers in
plan.objects) :unmarched? (not in a bounded march: a half-space or a field) :min
:color :near (its strategy's queries, see src/sdf/strategies.fnl)}, with what its
strategy adds (a group's :grid, a field's :field)."
  (let [out []]
    (var j 0)
    (each [_ o (ipairs (strategies.queried plan.tape))]
      (let [s (strategies.of o)
            n (s.count o)]
        (table.insert out (s.run plan o {:first (+ j 1) :last (+ j n)
                                         :unmarched? (not (s.marched? o))
                                         :min s.reference.min :color s.reference.color
                                         :near s.reference.near}))
        (set j (+ j n))))
    out))

;;; Queries over a run's objects one by one (a tree object, a group without a grid),
;;; and through a group's grid. (No closure in these: LuaJIT traces no function that
;;; makes one, and they run per point in a mesh.)

(fn each-min [r d x y z skip tape-distance _ ?dx ?dy ?dz]
  "d lowered by run `r`'s objects at x y z, but tape object number `skip`."
  (var d d)
  (for [i r.first r.last]
    (when (not= i skip)
      (let [di ((. tape-distance i) x y z ?dx ?dy ?dz)]
        (when (< di d) (set d di)))))
  d)

(fn visit [material i x y z d best r g b mirror rough emit modern?]
  ;; The colour query's state after tape object `i` at x y z: it wins when strictly
  ;; nearer. (Each `if` bound first: one as the last of `values` would be a closure.)
  (let [(di mr mg mb ma mk me) ((. material i) x y z)
        hit-rough (if modern? mk rough)
        hit-emit (if modern? me emit)]
    (if (< di d)
        (values di i mr mg mb ma hit-rough hit-emit)
        (values d best r g b mirror rough emit))))

(fn each-color [run x y z d best r g b mirror rough emit tape-distance tape-material modern?]
  "The colour query's state (see map-color-fn) after run `run`'s objects. An object's
material is read only where its distance (the same code without the material) is
below the nearest so far: one that is not could not win, and a material costs several
distances."
  (var (d best r g b mirror rough emit) (values d best r g b mirror rough emit))
  (for [i run.first run.last]
    (when (< ((. tape-distance i) x y z) d)
      (set (d best r g b mirror rough emit)
           (visit tape-material i x y z d best r g b mirror rough emit modern?))))
  (values d best r g b mirror rough emit))

(fn each-near [r x y z reach tape-distance]
  "How many of run `r`'s objects come within `reach` of x y z."
  (var near 0)
  (for [i r.first r.last]
    (when (< ((. tape-distance i) x y z) reach) (set near (+ near 1))))
  near)

(fn grid-min [r d x y z skip tape-distance draw ?dx ?dy ?dz]
  "each-min through a group's grid (r.grid): the members the point's cell lists and
the others' bound; along the ray ?dx ?dy ?dz a march skips members it is far from
(gridSkip)."
  (if (not r.grid)
      (each-min r d x y z skip tape-distance draw ?dx ?dy ?dz)
      (let [(start count bound) (grid.query r.grid x y z ?dx ?dy ?dz draw)
            records r.grid.records]
        (var d (if (< bound d) bound d))
        (for [s (+ start 1) (+ start count)]
          (let [member (. records s)
                i (+ r.first member)]
            (when (not= i skip)
              (let [di (or (and ?dx (grid.skip r.grid member x y z ?dx ?dy ?dz draw))
                           ((. tape-distance i) x y z))]
                (when (< di d) (set d di))))))
        d)))

(fn grid-color [run x y z d best r g b mirror rough emit tape-distance tape-material modern?]
  "each-color through a group's grid: its bound lowers d, not the colour (as
emit-glsl's terms)."
  (if (not run.grid)
      (each-color run x y z d best r g b mirror rough emit tape-distance tape-material modern?)
      (let [(start count bound) (grid.query run.grid x y z)]
        (var (d best r g b mirror rough emit) (values d best r g b mirror rough emit))
        (when (< bound d) (set d bound))
        (for [s (+ start 1) (+ start count)]
          (set (d best r g b mirror rough emit)
               (visit tape-material (+ run.first (. run.grid.records s)) x y z
                      d best r g b mirror rough emit modern?)))
        (values d best r g b mirror rough emit))))

(fn grid-near [r x y z reach tape-distance]
  "each-near through a group's grid: the members the point's cell lists."
  (if (not r.grid)
      (each-near r x y z reach tape-distance)
      (let [(start count) (grid.query r.grid x y z)]
        (var near 0)
        (for [s (+ start 1) (+ start count)]
          (when (< ((. tape-distance (+ r.first (. r.grid.records s))) x y z) reach)
            (set near (+ near 1))))
        near)))

(fn tape-min-fn [runs tape-distance draw]
  (fn [d x y z finite? skip ?dx ?dy ?dz]
    ;; d lowered by the tape's objects at x y z (with `finite?` those a bounded
    ;; march steps by: not the half-spaces, nor a field, whose grid it walks),
    ;; skipping tape object number `skip` (or none); grids bound their unlisted
    ;; members along the ray ?dx ?dy ?dz when a march gives one (mapFiniteAlong).
    (var d d)
    (each [_ r (ipairs runs)]
      (when (not (and finite? r.unmarched?))
        (set d (r.min r d x y z skip tape-distance draw ?dx ?dy ?dz))))
    d))

(fn near-count-fn [runs tape-distance]
  (fn [x y z reach]
    ;; How many of the tape's objects come within `reach` of x y z (less than a
    ;; grid's reach: the ones its cell lists).
    (var near 0)
    (each [_ r (ipairs runs)]
      (set near (+ near (r.near r x y z reach tape-distance))))
    near))

(fn planes-hit-fn [planes tape-distance tape-gradient draw]
  (fn [ox oy oz dx dy dz]
    ;; A half-space's distance s at the origin over the ray's rate v along its
    ;; normal (its gradient): 0 from inside, -s / v ahead (planesHit).
    (accumulate [t draw _ i (ipairs planes)]
      (let [s ((. tape-distance i) ox oy oz)
            (nx ny nz) ((. tape-gradient i) ox oy oz)
            v (+ (* dx nx) (* dy ny) (* dz nz))]
        (if (<= s 0) 0
            (< v 0) (math.min t (/ (- s) v))
            t)))))

(fn map-color-fn [runs tape-distance tape-material draw modern?]
  (fn [x y z]
    ;; Strictly smaller wins, so ties go to the earlier object in plan order (the
    ;; colours of a mesh's vertices took 13 microseconds each on machined-part
    ;; reading every material: see each-color).
    ;; Returns the distance, the index into plan.objects (or nil) and the colour and
    ;; mirror amount of the material found.
    ;; In the modern model also its roughness and emission (a field's objects:
    ;; matte, 0.5 and none; the classic model's are full mirrors).
    (var (d best) (values draw nil))
    (var (r g b mirror rough emit) (values 0 0 0 (if modern? 0 1) 0.5 0))
    (each [_ run (ipairs runs)]
      (set (d best r g b mirror rough emit)
           (run.color run x y z d best r g b mirror rough emit tape-distance tape-material modern?)))
    (values d best r g b mirror rough emit)))

(fn evaluators [ctx]
  "The distance field of a tracer's settings `ctx` (src/reference/settings.fnl): a
table of
  :map         (fn [x y z ?dx ?dy ?dz]) -> distance (never above the draw distance;
               along the ray ?dx ?dy ?dz in a march, grids skip far members)
  :map-finite  the same over the objects a bounded march steps by (no half-space,
               no field)
  :map-estimate, :map-finite-estimate
               map and map-finite read as estimates of the distance (a soft
               shadow's penumbra, occlusion; see :estimates? in lower.fnl)
  :planes-hit  (fn [ox oy oz dx dy dz]) -> where the ray meets the first half-space
  :map-color   (fn [x y z]) -> distance, index into plan.objects or nil, r g b,
               mirror, roughness, emission
  :near-count  (fn [x y z reach]) -> how many objects come within reach
  :others-map  (fn [i]) -> the distance to every object but plan.objects[i]
  :object-map  (fn [i]) -> the distance of plan.objects[i] alone"
  (let [{: plan : draw : tape-distance : tape-gradient : tape-material : modern? : tape-estimate} ctx
        runs (runs plan)
        tape-min (tape-min-fn runs tape-distance draw)
        estimate-min (if (= tape-estimate tape-distance) tape-min
                         (tape-min-fn runs tape-estimate draw))
        half-space (half-spaces plan)
        planes (fcollect [i 1 (length tape-distance)] (when (. half-space i) i))]
    {:map (fn [x y z ?dx ?dy ?dz] (tape-min draw x y z false nil ?dx ?dy ?dz))
     :map-finite (fn [x y z ?dx ?dy ?dz] (tape-min draw x y z true nil ?dx ?dy ?dz))
     ;; The same read as estimates of the distance (gEstimate in the shader).
     :map-estimate (fn [x y z] (estimate-min draw x y z false nil))
     :map-finite-estimate (fn [x y z] (estimate-min draw x y z true nil))
     :planes-hit (planes-hit-fn planes tape-distance tape-gradient draw)
     :map-color (map-color-fn runs tape-distance tape-material draw modern?)
     :near-count (near-count-fn runs tape-distance)
     ;; A field's objects through its grid, as the shader's (skipping i's number).
     :others-map (fn [i] (fn [x y z] (tape-min draw x y z false i)))
     :object-map (fn [i] (. tape-distance i))}))

{: evaluators : runs : half-spaces
 ;; The strategies' queries (src/sdf/strategies/):
 : each-min : each-color : each-near : grid-min : grid-color : grid-near : visit}

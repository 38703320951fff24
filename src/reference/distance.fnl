;; The CPU reference's distance field: the tape's objects folded as the shader folds
;; them (map, mapFinite, mapColor, mapOthers and planesHit), an object, an instance
;; group's members, a group with a grid (src/sdf/grid.fnl) or a field
;; (src/render/field.fnl) at a time.

(local field (require :src.render.field))
(local grid (require :src.sdf.grid))

(fn member-count [o]
  (if o.instances o.instances.count o.field o.field.count 1))

(fn half-spaces [plan]
  "Whether each tape object (by tape number) is a half-space, met in closed form with
bounds."
  (let [out {}]
    (var j 0)
    (each [_ o (ipairs plan.tape.objects)]
      (for [_ 1 (member-count o)]
        (set j (+ j 1))
        (tset out j o.half-space?)))
    out))

(fn runs [plan]
  "The tape's objects as the shader folds them, run by run: {:first :last
:half-space? :field :grid}, :field the plan's field for the field's run and :grid a
group's grid (the members its cell lists and the bound of the others, folded in
first)."
  (let [out []]
    (var j 0)
    (each [_ o (ipairs plan.tape.objects)]
      (let [n (member-count o)
            g (?. o :instances :grid)]
        (table.insert out {:first (+ j 1) :last (+ j n) :half-space? o.half-space?
                           :field (when o.field plan.field)
                           :grid (when g (. plan.grids.list (+ g 1) :grid))})
        (set j (+ j n))))
    out))

(fn tape-min-fn [runs tape-distance draw]
  (fn [d x y z finite? skip ?dx ?dy ?dz]
    ;; d lowered by the tape's objects at x y z (with `finite?` those a bounded
    ;; march steps by: not the half-spaces, nor a field, whose grid it walks),
    ;; skipping tape object number `skip` (or none); grids bound their unlisted
    ;; members along the ray ?dx ?dy ?dz when a march gives one (mapFiniteAlong).
    (var d d)
    (each [_ r (ipairs runs)]
      (when (not (and finite? (or r.half-space? r.field)))
        (if r.field
            ;; (No closure in this loop, nor in map-color-fn's: LuaJIT traces no
            ;; function that makes one, and these run per point in a mesh.)
            (let [own (and skip (+ 1 (- skip r.first)))
                  df (field.distance r.field x y z own)]
              (when (< df d) (set d df)))
            r.grid
            (let [(start count bound) (grid.query r.grid x y z ?dx ?dy ?dz draw)
                  records r.grid.records]
              (when (< bound d) (set d bound))
              (for [s (+ start 1) (+ start count)]
                (let [member (. records s)
                      i (+ r.first member)]
                  (when (not= i skip)
                    ;; A march skips members it is far from (gridSkip).
                    (let [di (or (and ?dx (grid.skip r.grid member x y z ?dx ?dy ?dz draw))
                                 ((. tape-distance i) x y z))]
                      (when (< di d) (set d di)))))))
            (for [i r.first r.last]
              (when (not= i skip)
                (let [di ((. tape-distance i) x y z ?dx ?dy ?dz)]
                  (when (< di d) (set d di))))))))
    d))

(fn near-count-fn [runs tape-distance]
  (fn [x y z reach]
    ;; How many of the tape's objects come within `reach` of x y z (less than a
    ;; grid's reach: the ones its cell lists).
    (var near 0)
    (each [_ r (ipairs runs)]
      (if r.grid
          (let [(start count) (grid.query r.grid x y z)]
            (for [s (+ start 1) (+ start count)]
              (when (< ((. tape-distance (+ r.first (. r.grid.records s))) x y z) reach)
                (set near (+ near 1)))))
          (for [i r.first r.last]
            (when (< ((. tape-distance i) x y z) reach) (set near (+ near 1))))))
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

(local black [0 0 0])

(fn visit [material i x y z d best r g b mirror rough emit modern?]
  ;; map-color-fn's state after tape object `i` at x y z: it wins when strictly nearer.
  ;; (Each `if` bound first: one as the last of `values` would be a closure.)
  (let [(di mr mg mb ma mk me) ((. material i) x y z)
        hit-rough (if modern? mk rough)
        hit-emit (if modern? me emit)]
    (if (< di d)
        (values di i mr mg mb ma hit-rough hit-emit)
        (values d best r g b mirror rough emit))))

(fn map-color-fn [runs tape-distance tape-material draw modern?]
  (fn [x y z]
    ;; Strictly smaller wins, so ties go to the earlier object in plan order. An
    ;; object's material is read only where its distance (the same code without the
    ;; material, or a bound below it) is below the nearest so far: one that is not
    ;; could not win, and a material costs several distances (the colours of a mesh's
    ;; vertices took 13 microseconds each on machined-part reading them all).
    ;; Returns the distance, the index into plan.objects (or nil) and the colour and
    ;; mirror amount of the material found.
    ;; In the modern model also its roughness and emission (a field's objects:
    ;; matte, 0.5 and none; the classic model's are full mirrors).
    (var (d best) (values draw nil))
    (var (r g b mirror rough emit) (values 0 0 0 (if modern? 0 1) 0.5 0))
    ;; A grid's bound lowers d, not the colour (as emit-glsl's looped).
    (each [_ run (ipairs runs)]
      (if run.field
          ;; A field's nearest listed member (black, and no object, outside its
          ;; grid), as fieldMap and fieldColor.
          (let [(df fb) (field.distance run.field x y z)]
            (when (< df d)
              (set d df)
              (set best (and fb (+ run.first fb -1)))
              (let [colour (if fb (. run.field.colors fb) black)
                    [cr cg cb] colour]
                (set (r g b) (values cr cg cb)))))
          run.grid
          (let [(start count bound) (grid.query run.grid x y z)]
            (when (< bound d) (set d bound))
            (for [s (+ start 1) (+ start count)]
              (set (d best r g b mirror rough emit)
                   (visit tape-material (+ run.first (. run.grid.records s)) x y z
                          d best r g b mirror rough emit modern?))))
          (for [i run.first run.last]
            (when (< ((. tape-distance i) x y z) d)
              (set (d best r g b mirror rough emit)
                   (visit tape-material i x y z d best r g b mirror rough emit modern?))))))
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

{: evaluators : runs : half-spaces}

;; The CPU reference marcher: the shader's semantics in plain LuaJIT, double precision,
;; written independently of the GLSL. Its distances come from the same descriptions as
;; the shader's (the tape's CPU evaluator, src/sdf/emit-lua.fnl, and a field's grid), so a GPU image can be checked pixel by pixel.
;;
;; Vectors travel as multiple values (x y z) and the inner loops allocate nothing.

(local camera (require :src.render.camera))
(local emit-lua (require :src.sdf.emit-lua))
(local bounds (require :src.render.bounds))
(local field (require :src.render.field))
(local grid (require :src.sdf.grid))
(local lighting (require :src.verify.lighting))

(local sqrt math.sqrt)
(local abs math.abs)

(fn clamp01 [v]
  (if (< v 0) 0 (> v 1) 1 v))

(fn normalize [x y z]
  (let [len (sqrt (+ (* x x) (* y y) (* z z)))]
    (values (/ x len) (/ y len) (/ z len))))

(fn heat-color [h]
  "The heat view's colour for h (steps / max-steps, clamped to [0, 1]): r g b."
  (let [h (clamp01 h)]
    (values (clamp01 (- 1.5 (abs (- (* 4 h) 3))))
            (clamp01 (- 1.5 (abs (- (* 4 h) 2))))
            (clamp01 (- 1.5 (abs (- (* 4 h) 1)))))))

(fn tracer [scene plan ?options]
  "A tracer for `scene` lowered to `plan`. Options: :cam-pos (the camera position,
which scaled hit tests measure distances from; default the origin), :pixel-angle
(1 / (projection distance * image height), for the :pixel hit test) and :counts (a
table the shaded view adds its distance evaluations to, as the shader makes them:
:primary, :shadow and :mirror march steps, :normal (differences; none for exact
normals) and :color (mapColor calls, one per hit)).
Returns a table of closures
  :map        (fn [x y z]) -> distance (never above the draw distance)
  :map-color  (fn [x y z]) -> distance, index into plan.objects or nil
  :march      (fn [ox oy oz dx dy dz]) -> t, steps
  :normal     (fn [x y z]) -> nx ny nz (plan.normals differences of the nearest
               object's distance, or with :normals-of :scene the whole scene's)
  :lightness  (fn [px py pz nx ny nz]) -> lambert, shadowed?
  :trace      (fn [ox oy oz dx dy dz]) -> {:color [r g b] :hit? :distance :steps
               :object (scene index or nil) :shadowed? :lightness :path :points}
               (shaded view: :points, the surface points along the path)
  :crease?    (fn [x y z]) -> whether two objects come within twice normal-delta
Positions are in world coordinates."
  (let [options (or ?options {})
        [cx cy cz] (or options.cam-pos [0 0 0])
        pixel-angle (or options.pixel-angle 0)
        counts options.counts
        render scene.render
        draw render.draw-distance
        eps render.epsilon
        max-steps render.max-steps
        relaxation (if plan.relaxed? render.relaxation 1)
        hit-test plan.hit-test
        normal-method (or plan.normals :one-sided)
        [lx ly lz] scene.light.pos
        [er eg eb] scene.environment
        view plan.view
        shaded? (= view :shaded)
        shadows? (and shaded? plan.shadows?)
        glow? (and shaded? plan.glow?)
        reflections (if (and shaded? plan.reflections?) plan.reflections 0)
        modern? (or (not= nil plan.lighting) (and plan.tape (= plan.tape.material-size 8)))
        ;; The field (lower.fnl's :field strategy): its grid, when the tape has one.
        fd plan.field
        tape (emit-lua.compile plan.tape)
        tape-distance tape.distance
        tape-material tape.material
        tape-gradient tape.gradient
        m (length tape-distance)
        ;; The tape's half-spaces (by tape number), met in closed form with bounds.
        half-space (let [out {}]
                     (var j 0)
                     (each [_ o (ipairs plan.tape.objects)]
                       (for [_ 1 (if o.instances o.instances.count o.field o.field.count 1)]
                         (set j (+ j 1))
                         (tset out j o.half-space?)))
                     out)
        ;; The tape's objects as the shader folds them, run by run: an object, an
        ;; instance group's members, a group with a grid (src/sdf/grid.fnl): the
        ;; members its cell lists and the bound of the others, folded in first, or a
        ;; field (src/render/field.fnl: its grid's distance, as fieldMap).
        runs (let [out []]
               (var j 0)
               (each [_ o (ipairs plan.tape.objects)]
                 (let [n (if o.instances o.instances.count o.field o.field.count 1)
                       g (?. o :instances :grid)]
                   (table.insert out {:first (+ j 1) :last (+ j n) :half-space? o.half-space?
                                      :field (when o.field fd)
                                      :grid (when g (. plan.grids.list (+ g 1) :grid))})
                   (set j (+ j n))))
               out)]

    (fn tape-min [d x y z finite? skip ?dx ?dy ?dz]
      ;; d lowered by the tape's objects at x y z (with `finite?` those a bounded
      ;; march steps by: not the half-spaces, nor a field, whose grid it walks),
      ;; skipping tape object number `skip` (or none); grids bound their unlisted
      ;; members along the ray ?dx ?dy ?dz when a march gives one (mapFiniteAlong).
      (var d d)
      (each [_ r (ipairs runs)]
        (when (not (and finite? (or r.half-space? r.field)))
          (if r.field
              (let [df (field.distance r.field x y z (when skip (+ 1 (- skip r.first))))]
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
      d)

    (fn near-count [x y z reach]
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
      near)

    (fn map [x y z ?dx ?dy ?dz]
      ;; (Along the ray ?dx ?dy ?dz in a march: see tape-min.)
      (tape-min draw x y z false nil ?dx ?dy ?dz))

    ;; With bounds (src/render/bounds.fnl), as the shader: the half-spaces met in
    ;; closed form, the other objects marched over the span of their bounding spheres.
    (local planes (fcollect [i 1 m] (when (. half-space i) i)))

    (fn map-finite [x y z ?dx ?dy ?dz]
      (tape-min draw x y z true nil ?dx ?dy ?dz))

    (fn planes-hit [ox oy oz dx dy dz]
      ;; A half-space's distance s at the origin over the ray's rate v along its
      ;; normal (its gradient): 0 from inside, -s / v ahead (planesHit).
      (accumulate [t draw _ i (ipairs planes)]
        (let [s ((. tape-distance i) ox oy oz)
              (nx ny nz) ((. tape-gradient i) ox oy oz)
              v (+ (* dx nx) (* dy ny) (* dz nz))]
          (if (<= s 0) 0
              (< v 0) (math.min t (/ (- s) v))
              t))))

    (fn map-color [x y z]
      ;; Strictly smaller wins, so ties go to the earlier object in plan order.
      ;; Returns the distance, the index into plan.objects (or nil) and the colour and
      ;; mirror amount of the material found.
      ;; In the modern model also its roughness and emission (a field's objects:
      ;; matte, 0.5 and none; the classic model's are full mirrors).
      (var d draw)
      (var best nil)
      (var (r g b mirror rough emit) (values 0 0 0 (if modern? 0 1) 0.5 0))
      (fn visit [i]
        (let [(di mr mg mb ma mk me) ((. tape-material i) x y z)]
          (when (< di d)
            (set d di)
            (set best i)
            (set (r g b mirror) (values mr mg mb ma))
            (when modern? (set (rough emit) (values mk me))))))
      ;; A grid's bound lowers d, not the colour (as emit-glsl's looped).
      (each [_ run (ipairs runs)]
        (if run.field
            ;; A field's nearest listed member (black, and no object, outside its
            ;; grid), as fieldMap and fieldColor.
            (let [(df fb) (field.distance run.field x y z)]
              (when (< df d)
                (set d df)
                (set best (when fb (+ run.first fb -1)))
                (let [[cr cg cb] (if fb (. run.field.colors fb) [0 0 0])]
                  (set (r g b) (values cr cg cb)))))
            run.grid
            (let [(start count bound) (grid.query run.grid x y z)]
              (when (< bound d) (set d bound))
              (for [s (+ start 1) (+ start count)]
                (visit (+ run.first (. run.grid.records s)))))
            (for [i run.first run.last] (visit i))))
      (values d best r g b mirror rough emit))

    (fn threshold [dist]
      ;; The hit test: a step shorter than this is a hit. dist is the distance from
      ;; the camera along the ray's path.
      (case hit-test
        :fixed eps
        :relative (* eps dist)
        :pixel (* eps dist pixel-angle)))

    (fn start-limit [d]
      ;; The nearest a secondary ray may come to count a hit, given the distance d at
      ;; its start (startLimit in shaders/pipeline/hit/): half of it, except in the
      ;; article's fixed test or from inside a solid.
      (if (or (= hit-test :fixed) (<= d 0)) draw (* 0.5 d)))

    (fn distance-from-camera [x y z]
      (let [ex (- x cx) ey (- y cy) ez (- z cz)]
        (sqrt (+ (* ex ex) (* ey ey) (* ez ez)))))

    (fn normal-delta [x y z]
      ;; Finite-difference step and (twice it) the offset of secondary rays.
      (let [dist (distance-from-camera x y z)]
        (math.max (threshold dist) (* 0.000001 (+ 1 dist)))))

    (local bound-spheres (when plan.bounds
                           (bounds.spheres plan [cx cy cz] threshold true)))

    ;; A field's marched members' hit test (field.fnl's marched-entry): the march's.
    (local field-hit {:t0 0 : threshold : start-limit})

    (fn march-field [ox oy oz dx dy dz ?t-max]
      ;; march.glsl's field walk: the grid's cells in order, each cell's objects met in
      ;; closed form (a marched member sphere-traced alone) and the other finite
      ;; objects sphere-traced, a step never past the cell's far wall.
      (let [t0 (distance-from-camera ox oy oz)
            _ (set field-hit.t0 t0)
            t-plane (planes-hit ox oy oz dx dy dz)
            (enter exit) (bounds.span bound-spheres ox oy oz dx dy dz draw)
            ;; kFieldOthers: finite objects beside the field.
            others? (> plan.bounds.count 0)
            ;; A field of spheres alone walks lists of its own (march.glsl's spheres' walk).
            walk (when (and fd.walk? (not others?)) fd.walk)
            cell-count (if walk walk.count fd.cell-count)
            [lx ly lz] fd.lo
            [wx wy wz] fd.size
            [sx sy sz] fd.cell
            [nx ny nz] fd.dims
            qx (- ox lx) qy (- oy ly) qz (- oz lz)
            (ix iy iz) (field.reciprocal dx dy dz)
            near (fn [q w i] (math.min (* (- q) i) (* (- w q) i)))
            far (fn [q w i] (math.max (* (- q) i) (* (- w q) i)))
            grid-in (math.max (near qx wx ix) (near qy wy iy) (near qz wz iz) 0)
            grid-out (math.min (far qx wx ix) (far qy wy iy) (far qz wz iz))
            grid? (< grid-in grid-out)
            t-end (math.min t-plane (math.max exit (if grid? grid-out 0)) (or ?t-max draw))
            t-past (math.min t-plane (or ?t-max draw))
            max-iterations (+ max-steps fd.crossings 1)
            step-x (if (> ix 0) 1 -1) step-y (if (> iy 0) 1 -1) step-z (if (> iz 0) 1 -1)
            delta-x (* sx (abs ix)) delta-y (* sy (abs iy)) delta-z (* sz (abs iz))]
        (var t (math.max (math.min enter (if grid? grid-in draw)) 0))
        (var state (if grid? 0 2))
        (var cell-end (if grid? grid-in draw))
        (var (cx cy cz) (values 0 0 0))
        (var (next-x next-y next-z) (values 0 0 0))
        (var evals 0)
        (var result nil)
        (var start-half draw)
        (var first? true)
        (when (>= t t-end) (set result t-past))
        (for [_ 1 max-iterations &until result]
          (when (and (= state 0) (>= t grid-in))
            (let [(x y z) (field.cell-of fd (+ qx (* dx t)) (+ qy (* dy t)) (+ qz (* dz t)))]
              (set (cx cy cz) (values x y z))
              (set next-x (* (- (* (+ cx (if (> step-x 0) 1 0)) sx) qx) ix))
              (set next-y (* (- (* (+ cy (if (> step-y 0) 1 0)) sy) qy) iy))
              (set next-z (* (- (* (+ cz (if (> step-z 0) 1 0)) sz) qz) iz))
              (set state 1)
              (set cell-end (math.min next-x next-y next-z))))
          (let [px (+ ox (* dx t)) py (+ oy (* dy t)) pz (+ oz (* dz t))]
            (var d (map-finite px py pz dx dy dz))
            (when (and first? (= t 0) (> t0 0)) (set start-half (start-limit d)))
            (set first? false)
            (var evaluated? others?)
            (when (= state 1)
              (let [k (+ 1 cx (* nx (+ cy (* ny cz))))]
                (when (> (. cell-count k) 0)
                  ;; The cell's objects in closed form (fieldListEntry): an entry in
                  ;; the cell, before any other object can be, is the hit.
                  (let [hit (field.list-entry fd k qx qy qz dx dy dz ix iy iz draw walk field-hit)]
                    (set evaluated? true)
                    (when (and (<= hit (math.min (+ t d) cell-end)) (< hit t-end))
                      (set evals (+ evals 1))
                      (set result hit))))))
            (when (and evaluated? (not result))
              (set evals (+ evals 1))
              (when (< d (math.min (threshold (+ t0 t)) start-half))
                (set result (+ t d))))
            (when (not result)
              (if (< (+ t d) cell-end)
                  (set t (+ t d))
                  (do
                    (set t (math.max t cell-end))
                    (when (= state 1)
                      ;; On along the axis (or axes, at a tie) whose wall comes first.
                      (let [mx (<= next-x (math.min next-y next-z))
                            my (<= next-y (math.min next-z next-x))
                            mz (<= next-z (math.min next-x next-y))]
                        (when mx (set cx (+ cx step-x)) (set next-x (+ next-x delta-x)))
                        (when my (set cy (+ cy step-y)) (set next-y (+ next-y delta-y)))
                        (when mz (set cz (+ cz step-z)) (set next-z (+ next-z delta-z))))
                      (if (or (< cx 0) (< cy 0) (< cz 0) (>= cx nx) (>= cy ny) (>= cz nz))
                          (do (set state 2) (set cell-end draw))
                          (set cell-end (math.min next-x next-y next-z))))))
              (if (>= t t-end) (set result t-past)
                  (>= evals max-steps) (set result :out)))))
        (if (and result (not= result :out)) (values result evals)
            ;; Out of steps (see codegen's out-of-steps).
            (values (if (= plan.out-of-steps :background) t-past t) evals))))

    (fn march-plain [ox oy oz dx dy dz ?t-max]
      ;; Plain sphere tracing when relaxation is 1; over-relaxed (Keinert et al.)
      ;; with a fall back to the last safe point when two spheres stop overlapping.
      ;; With bounds: from the span's entry to its exit or the nearest plane, and
      ;; the plane's distance when the ray passes the end.
      (let [t0 (distance-from-camera ox oy oz)
            f (if bound-spheres map-finite map)
            t-plane (if bound-spheres (planes-hit ox oy oz dx dy dz) draw)
            (enter exit) (if bound-spheres (bounds.span bound-spheres ox oy oz dx dy dz draw)
                             (values 0 draw))
            t-end (math.min t-plane exit (or ?t-max draw))]
        (var t (math.max enter 0))
        (var t-prev t)
        (var r-prev 0)
        (var omega relaxation)
        (var steps 0)
        ;; A secondary ray (t0 > 0; primary rays start at the camera) whose first
        ;; step is at its start must come nearer than start-limit of the distance
        ;; there to count a hit, so one starting inside the hit threshold (in a
        ;; crease) never hits at its start (march.glsl's startHalf).
        (var start-half draw)
        ;; Past the end: the plane when it comes before the limit, else the limit
        ;; (a miss).
        (local t-past (math.min t-plane (or ?t-max draw)))
        (var done? (and bound-spheres (>= t t-end)))
        (when done? (set t t-past))
        (for [i 0 (- max-steps 1) &until done?]
          (let [d (f (+ ox (* dx t)) (+ oy (* dy t)) (+ oz (* dz t)) dx dy dz)]
            (set steps (+ i 1))
            (when (and (= i 0) (= t 0) (> t0 0)) (set start-half (start-limit d)))
            (if (and (> omega 1) (< (+ (abs d) r-prev) (- t t-prev)))
                (do (set t (+ t-prev r-prev))
                    (set omega 1))
                (< d (math.min (threshold (+ t0 t)) start-half))
                (do (set t (+ t d))
                    (set done? true))
                (do (set t-prev t)
                    (set r-prev (abs d))
                    (set t (+ t (* omega d)))
                    (when (>= t t-end)
                      (if (not bound-spheres) (set done? true)
                          ;; An over-relaxed step past the end may have jumped a
                          ;; surface: only a plain step past it ends the march.
                          (>= (+ t-prev r-prev) t-end) (do (set t t-past) (set done? true))
                          (do (set t (+ t-prev r-prev))
                              (set omega 1))))))))
        ;; Out of steps without a hit: the article shades where the ray stopped;
        ;; :background lets it pass the finite objects (see codegen's out-of-steps).
        (when (and (not done?) (= plan.out-of-steps :background))
          (set t (if bound-spheres t-past draw)))
        (values t steps)))

    (fn march [ox oy oz dx dy dz ?t-max]
      (if fd (march-field ox oy oz dx dy dz ?t-max)
          (march-plain ox oy oz dx dy dz ?t-max)))

    (fn tally [key n]
      (when counts (tset counts key (+ (or (. counts key) 0) n))))

    (fn safe-normalize [x y z]
      (let [len (sqrt (+ (* x x) (* y y) (* z z)))]
        (if (> len 0) (values (/ x len) (/ y len) (/ z len)) (values 0 0 1))))

    (fn object-map [i]
      ;; The distance function of plan.objects[i] alone.
      (. tape-distance i))

    (fn crease? [x y z]
      ;; Two objects meet within the normal's finite-difference reach of the point:
      ;; a whole-scene normal there points between their surfaces.
      (let [reach (* 2 (normal-delta x y z))]
        (>= (near-count x y z reach) 2)))

    (fn others-map [i]
      ;; The distance to every object but plan.objects[i] (mapOthers).
      ;; A field's objects through its grid, as the shader's (skipping i's number).
      (fn [x y z]
        (tape-min draw x y z false i)))

    (fn differences [map x y z h]
      (tally :normal (if (= normal-method :central) 6 4))
      (case normal-method
          :one-sided (let [d (map x y z)]
                       (safe-normalize (- d (map (- x h) y z))
                                       (- d (map x (- y h) z))
                                       (- d (map x y (- z h)))))
          :central (safe-normalize (- (map (+ x h) y z) (map (- x h) y z))
                                   (- (map x (+ y h) z) (map x (- y h) z))
                                   (- (map x y (+ z h)) (map x y (- z h))))
          :tetrahedron (let [a (map (+ x h) (- y h) (- z h))   ; k.xyy
                             b (map (- x h) (- y h) (+ z h))   ; k.yyx
                             c (map (- x h) (+ y h) (- z h))   ; k.yxy
                             e (map (+ x h) (+ y h) (+ z h))]  ; k.xxx
                         (safe-normalize (+ a (- b) (- c) e)
                                         (+ (- a) (- b) c e)
                                         (+ (- a) b (- c) e)))))

    (fn normal [x y z]
      ;; The whole scene's differences with :normals-of :scene (or when no object is
      ;; near); else the nearest object's exact gradient when it has one (a field's
      ;; object or a leaf's: normal-exact.glsl), or its own differences (mapObject),
      ;; taken where another object comes within 2h at the point pushed out of its
      ;; reach (normal-crease.glsl).
      (let [h (normal-delta x y z)
            (_ i) (map-color x y z)]
        (if (and plan.exact-normals? (not i))
            (values 0 0 1)
            (or (= plan.normals-of :scene) (not i))
            (differences map x y z h)
            (. tape-gradient i)
            ((. tape-gradient i) x y z)
            (let [others (others-map i)
                  other (others x y z)]
              (tally :normal (if (< other (* 2 h)) 7 1))
              (if (< other (* 2 h))
                  (let [(ax ay az) (safe-normalize (- (others (+ x h) y z) (others (- x h) y z))
                                                   (- (others x (+ y h) z) (others x (- y h) z))
                                                   (- (others x y (+ z h)) (others x y (- z h))))
                        push (- (* 2 h) other)]
                    (differences (object-map i) (+ x (* ax push)) (+ y (* ay push)) (+ z (* az push)) h))
                  (differences (object-map i) x y z h))))))

    (fn lightness [px py pz nx ny nz]
      (let [tx (- lx px) ty (- ly py) tz (- lz pz)
            len (sqrt (+ (* tx tx) (* ty ty) (* tz tz)))
            ;; A light exactly at the point lights it along its normal.
            (ldx ldy ldz) (if (> len 0) (values (/ tx len) (/ ty len) (/ tz len))
                              (values nx ny nz))
            lambert (clamp01 (+ (* ldx nx) (* ldy ny) (* ldz nz)))]
        (if (and shadows? (> lambert 0))
            ;; With bounds the shadow ray ends at the light (shadow-to-light.glsl);
            ;; the article's goes on to the draw distance.
            (let [s (* 2 (normal-delta px py pz))
                  limit (if bound-spheres (math.min (- len (* 2 (normal-delta lx ly lz))) draw) draw)
                  (ts steps) (march (+ px (* nx s)) (+ py (* ny s)) (+ pz (* nz s)) ldx ldy ldz limit)]
              (tally :shadow steps)
              (if (< ts limit) (values (* lambert 0.5) true) (values lambert false)))
            (values lambert false))))

    (fn object-index [i]
      (when i (. plan.objects i :index)))

    (var modern-shade nil)

    (fn trace [ox oy oz dx dy dz]
      (let [(t steps) (march ox oy oz dx dy dz)
            _ (tally :primary steps)
            hit? (< t draw)
            result {:hit? hit? :distance t :steps steps :path []}]
        (var (r g b) (values 0 0 0))
        (if (and shaded? modern-shade)
            (let [(mr mg mb path points) (modern-shade ox oy oz dx dy dz t)]
              (set (r g b) (values mr mg mb))
              (set result.path path)
              (set result.points points)
              (when hit?
                (let [(_ i) (map-color (+ ox (* dx t)) (+ oy (* dy t)) (+ oz (* dz t)))]
                  (set result.object (object-index i)))))
            (= view :heat)
            (do (set (r g b) (heat-color (/ steps max-steps)))
                (when hit?
                  (let [(_ i) (map-color (+ ox (* dx t)) (+ oy (* dy t)) (+ oz (* dz t)))]
                    (set result.object (object-index i))
                    (table.insert result.path (or (object-index i) 0)))))
            (not hit?)
            (if (= view :glow) (let [grey (/ steps 100)] (set (r g b) (values grey grey grey)))
                (= view :normals) nil
                ;; shaded
                (let [glow (if glow? (/ steps 100) 0)]
                  (set (r g b) (values (+ er glow) (+ eg glow) (+ eb glow)))))
            (let [px (+ ox (* dx t)) py (+ oy (* dy t)) pz (+ oz (* dz t))
                  (_ i) (map-color px py pz)]
              (set result.object (object-index i))
              (table.insert result.path (or (object-index i) 0))
              (set result.points [[px py pz]])
              (case view
                :glow (let [(_ _ cr cg cb) (map-color px py pz)]
                        (set (r g b) (values cr cg cb)))
                :normals (let [(nx ny nz) (normal px py pz)]
                           (set (r g b) (values (+ (* nx 0.5) 0.5) (+ (* ny 0.5) 0.5)
                                                (+ (* nz 0.5) 0.5))))
                :shaded
                (let [(nx ny nz) (normal px py pz)
                      (_ _ cr cg cb primary-mirror) (map-color px py pz)
                      _ (tally :color 1)
                      (lambert shadowed?) (lightness px py pz nx ny nz)]
                  (set result.lightness lambert)
                  (set result.shadowed? shadowed?)
                  (set (r g b) (values (* cr lambert) (* cg lambert) (* cb lambert)))
                  ;; Mirror bounces.
                  (var (qx qy qz) (values px py pz))
                  (var (mx my mz) (values nx ny nz))
                  (var (vx vy vz) (values dx dy dz))
                  (var stop? false)
                  ;; Part mirrors (plan.mirrors?): each bounce is mixed with the colour
                  ;; before it by the mirror amount of the surface the ray leaves.
                  (var mirror (if plan.mirrors? primary-mirror 1))
                  (fn mix-in [br bg bb]
                    (if plan.mirrors?
                        (set (r g b) (values (+ br (* (- r br) mirror)) (+ bg (* (- g bg) mirror))
                                             (+ bb (* (- b bb) mirror))))))
                  (for [bounce 1 reflections &until stop?]
                    (when (<= mirror 0) (set stop? true))
                    (let [(br bg bb) (values r g b)
                          k (* 2 (+ (* vx mx) (* vy my) (* vz mz)))
                          rx (- vx (* k mx)) ry (- vy (* k my)) rz (- vz (* k mz))
                          s (* 2 (normal-delta qx qy qz))
                          sx (+ qx (* mx s)) sy (+ qy (* my s)) sz (+ qz (* mz s))
                          (tr mirror-steps) (march sx sy sz rx ry rz)]
                      (when (not stop?) (tally :mirror mirror-steps))
                      (if stop? nil
                          (>= tr draw)
                          (do (set (r g b) (values (* (+ r (/ er bounce)) 0.5)
                                                   (* (+ g (/ eg bounce)) 0.5)
                                                   (* (+ b (/ eb bounce)) 0.5)))
                              (mix-in br bg bb)
                              (table.insert result.path -1)
                              (set stop? true))
                          (let [hx (+ sx (* rx tr)) hy (+ sy (* ry tr)) hz (+ sz (* rz tr))
                                (hnx hny hnz) (normal hx hy hz)
                                (_ j hr hg hb hit-mirror) (map-color hx hy hz)
                                _ (tally :color 1)
                                hl (* (lightness hx hy hz hnx hny hnz) 0.5)]
                            (table.insert result.path (or (object-index j) 0))
                            (table.insert result.points [hx hy hz])
                            (set (qx qy qz) (values hx hy hz))
                            (set (mx my mz) (values hnx hny hnz))
                            (set (vx vy vz) (values rx ry rz))
                            (set (r g b) (values (* (+ r (* hr hl)) 0.66)
                                                 (* (+ g (* hg hl)) 0.66)
                                                 (* (+ b (* hb hl)) 0.66)))
                            (mix-in br bg bb)
                            (set mirror hit-mirror))))))
                _ (error (.. "reference: unknown view " (tostring view))))))
        (set result.color [(clamp01 r) (clamp01 g) (clamp01 b)])
        result))

    (fn needs-samples? [ox oy oz dx dy dz t]
      ;; Adaptive supersampling's edge tests on a centre ray that went t with `steps`
      ;; (see shaders/pipeline/adaptive.glsl and plan.edge-tests).
      (let [tests plan.edge-tests]
        (if (>= t draw) false
            (let [px (+ ox (* dx t)) py (+ oy (* dy t)) pz (+ oz (* dz t))
                  (nx ny nz) (normal px py pz)
                  e (* t pixel-angle)
                  qx (+ px (* dx e)) qy (+ py (* dy e)) qz (+ pz (* dz e))
                  h (* 0.5 e)
                  (ax ay az) (safe-normalize (- (map (+ qx h) qy qz) (map (- qx h) qy qz))
                                             (- (map qx (+ qy h) qz) (map qx (- qy h) qz))
                                             (- (map qx qy (+ qz h)) (map qx qy (- qz h))))
                  turn (- 1 (+ (* nx ax) (* ny ay) (* nz az)))
                  facing (- (+ (* nx dx) (* ny dy) (* nz dz)))]
              (or (> turn tests.edge-turn)
                  (and (< facing tests.grazing) (> turn tests.limb-turn)))))))

    ;; Soft shadows over the span of the bounding spheres grown by `grow` (see
    ;; plan.lighting.soft-bounded? in src/render/plan.fnl).
    (local soft-span (when (?. plan :lighting :soft-bounded?)
                       (fn [ox oy oz dx dy dz grow]
                         (bounds.span bound-spheres ox oy oz dx dy dz draw grow))))
    (local closures {: map : map-color : march : normal : lightness : trace : normal-delta : crease?
                     : needs-samples? : map-finite : planes-hit : soft-span
                     : threshold : start-limit : distance-from-camera})
    (when (and shaded? plan.lighting)
      (set modern-shade (lighting.shader closures scene plan)))
    closures))

(fn ray-setup [cam width height]
  "A function (px py ?sx ?sy) -> dx dy dz giving the primary ray through pixel
(px, py), 0-based from the top-left of a width x height target, at (?sx, ?sy) inside
it (0..1; default its centre, 0.5 0.5)."
  (let [(f r u) (camera.basis cam)
        pd (camera.projection-distance cam)
        [fx fy fz] f [rx ry rz] r [ux uy uz] u
        aspect (/ width height)]
    (fn [px py ?sx ?sy]
      (let [uvx (* (- (/ (+ px (or ?sx 0.5)) width) 0.5) aspect)
            uvy (- (/ (+ py (or ?sy 0.5)) height) 0.5)]
        (normalize (+ (* fx pd) (* rx uvx) (* ux uvy))
                   (+ (* fy pd) (* ry uvx) (* uy uvy))
                   (+ (* fz pd) (* rz uvx) (* uz uvy)))))))

(fn render-pixels [scene plan cam width height pixels ?counts]
  "Reference colours of `pixels` (a list of [x y], 0-based from the top-left) of a
width x height image of `scene` lowered to `plan` seen by camera state `cam`.
Returns a list of {:x :y :color [r g b] (0..1, clamped) :hit? :distance t :steps n
:object (scene index of the object hit, or nil) :shadowed? :lightness :path}, in the
order of `pixels`. :path lists the scene index of the object hit by the primary ray
and each bounce (-1: the bounce escaped). With supersampling (plan.samples N > 1) the
colour is the mean of N x N rays on a grid inside the pixel, each clamped, as the
shader's; the other fields are the first ray's. Adaptive (plan.adaptive?): the centre
ray's result with the colour the mean of it and a second ray's (plan.edge-tests),
unless the centre ray finds an edge or the two differ (then :edge? is true and the
colour is the grid's mean). `?counts` gathers the distance evaluations (see tracer)."
  (let [T (tracer scene plan {:cam-pos cam.pos :counts ?counts
                             :pixel-angle (/ 1 (* (camera.projection-distance cam) height))})
        ray (ray-setup cam width height)
        [ox oy oz] cam.pos
        n (or plan.samples 1)]
    (icollect [_ [x y] (ipairs pixels)]
      (let [centre (when (or (= n 1) plan.adaptive?) (T.trace ox oy oz (ray x y)))
            tests plan.edge-tests
            geometric? (and plan.adaptive?
                            (let [(dx dy dz) (ray x y)]
                              (T.needs-samples? ox oy oz dx dy dz centre.distance)))
            ;; No edge on the centre ray: a second ray, and the grid only when its
            ;; colour's luma differs by more than tests.contrast (adaptive.glsl).
            second (when (and plan.adaptive? (not geometric?))
                     (T.trace ox oy oz (ray x y (. tests.second 1) (. tests.second 2))))
            contrast? (when second
                        (let [[r1 g1 b1] centre.color [r2 g2 b2] second.color]
                          (> (math.abs (+ (* 0.2126 (- r2 r1)) (* 0.7152 (- g2 g1)) (* 0.0722 (- b2 b1))))
                             tests.contrast)))
            edge? (or geometric? contrast?)
            result (if (= n 1) centre
                       (and plan.adaptive? (not edge?))
                       (doto centre
                         (tset :color (icollect [i c (ipairs centre.color)]
                                        (* 0.5 (+ c (. second.color i))))))
                       (let [sum [0 0 0]]
                         (var first nil)
                         (for [j 0 (- n 1)]
                           (for [i 0 (- n 1)]
                             (let [r (T.trace ox oy oz (ray x y (/ (+ i 0.5) n) (/ (+ j 0.5) n)))]
                               (when (not first) (set first r))
                               (for [c 1 3] (tset sum c (+ (. sum c) (. r.color c)))))))
                         (set first.color (icollect [_ v (ipairs sum)] (/ v (* n n))))
                         first))]
        (set result.x x)
        (set result.y y)
        (when plan.adaptive? (set result.edge? edge?))
        result))))

{: tracer : ray-setup : render-pixels : heat-color}

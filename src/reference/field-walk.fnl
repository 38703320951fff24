;; The CPU reference's march through a field (src/render/field.fnl): march.glsl's field
;; walk, the grid's cells in order.

(local bounds (require :src.render.bounds))
(local field (require :src.render.field))

(local abs math.abs)

(fn walker [ctx parts]
  "The field walk of a tracer's settings `ctx` (src/reference/settings.fnl, with a
field) over `parts` (the tracer's distance field, hit tests and :bound-spheres):
(fn [ox oy oz dx dy dz ?t-max]) -> t, distance evaluations, as the march."
  (let [{: plan : fd : draw : max-steps} ctx
        {: distance-from-camera : planes-hit : map-finite : threshold : start-limit
         : bound-spheres} parts
        ;; A field's marched members' hit test (field.fnl's marched-entry): the march's.
        field-hit {:t0 0 : threshold : start-limit}]
    (fn [ox oy oz dx dy dz ?t-max]
      ;; march.glsl's field walk: the grid's cells in order, each cell's objects met in
      ;; closed form (a marched member sphere-traced alone) and the other finite
      ;; objects sphere-traced, a step never past the cell's far wall.
      (let [t0 (distance-from-camera ox oy oz)
            _ (set field-hit.t0 t0)
            t-plane (planes-hit ox oy oz dx dy dz)
            (enter exit) (bounds.span bound-spheres ox oy oz dx dy dz draw)
            ;; fieldOthers(): finite objects beside the field (their bounding spheres).
            others? (> (length bound-spheres) 0)
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
            (values (if (= plan.out-of-steps :background) t-past t) evals))))))

{: walker}

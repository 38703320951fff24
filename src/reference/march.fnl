;; The CPU reference's march: sphere tracing, plain or over-relaxed, over the whole
;; scene or the span of the bounding spheres (src/render/bounds.fnl), or a field's
;; walk (src/reference/field-walk.fnl).

(local bounds (require :src.render.bounds))
(local field-walk (require :src.reference.field-walk))

(local abs math.abs)

(fn plain-marcher [ctx parts]
  "Sphere tracing for a tracer's settings `ctx` over `parts` (its distance field, hit
tests and :bound-spheres): (fn [ox oy oz dx dy dz ?t-max]) -> t, steps."
  (let [{: plan : draw : max-steps : relaxation} ctx
        {: distance-from-camera : planes-hit : map : map-finite : threshold : start-limit
         : bound-spheres} parts]
    (fn [ox oy oz dx dy dz ?t-max]
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
        (values t steps)))))

(fn marcher [ctx parts]
  "The primary march of a tracer's settings `ctx` (src/reference/settings.fnl) over
`parts` (its distance field, hit tests and :bound-spheres): (fn [ox oy oz dx dy dz
?t-max]) -> t, steps (distance evaluations). t is ?t-max or the draw distance (or the
nearest plane's) on a miss."
  (if ctx.fd
      (field-walk.walker ctx parts)
      (plain-marcher ctx parts)))

{: marcher}

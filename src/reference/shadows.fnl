;; The modern model's shadows on the CPU (shaders/shading/shadow*.glsl): how much of a
;; light reaches a point, hard or soft.

(local {: clamp01} (require :src.reference.vec))

(local sqrt math.sqrt)
(local max math.max)
(local min math.min)

(fn soft-visibility-fn [T draw shadow-steps]
  (let [map T.map
        threshold T.threshold]
    (fn [ox oy oz lx ly lz reach softness]
      ;; Quilez's improved penumbra estimate, as shadow-soft.glsl; with bounds only
      ;; over the span of the bounding spheres grown by the penumbra (codegen's
      ;; soft-span-lines), the planes met in closed form.
      (let [t0 (T.distance-from-camera ox oy oz)
            f (if T.soft-span T.map-finite map)
            ;; The penumbra's reading of the field (gEstimate): the same function
            ;; without estimates.
            fe (if (not T.estimates?) f T.soft-span T.map-finite-estimate T.map-estimate)]
        (var seen 1)
        (var t 0)
        (var h-prev 1e10)
        (var he-prev 1e10)
        ;; As the marches: a hit must come nearer than start-limit of the start's
        ;; distance.
        (var start-half 1e10)
        (var first? true)
        (var result nil)
        (var limit reach)
        (when T.soft-span
          (if (< (T.planes-hit ox oy oz lx ly lz) reach)
              (set result 0)
              (let [(enter exit) (if (< softness 0.5)
                                     (T.soft-span ox oy oz lx ly lz (/ softness (- 1 softness)))
                                     (values 0 draw))]
                (set t (max enter 0))
                (set limit (min reach exit))
                (when (>= t limit) (set result -1)))))
        (for [_ 1 shadow-steps &until result]
          (let [h (f (+ ox (* lx t)) (+ oy (* ly t)) (+ oz (* lz t)))
                he (if (= fe f) h (fe (+ ox (* lx t)) (+ oy (* ly t)) (+ oz (* lz t))))]
            (when (and first? (= t 0)) (set start-half (T.start-limit h)))
            (set first? false)
            (if (< h (min (threshold (+ t0 t)) start-half))
                (set result 0)
                (let [y (if (= fe f) (/ (* he he) (* 2 he-prev))
                            ;; The chord of spheres he-prev and he, h-prev apart.
                            (/ (+ (- (* h-prev h-prev) (* he-prev he-prev)) (* he he)) (* 2 h-prev)))
                      closest (sqrt (max (- (* he he) (* y y)) 0))]
                  ;; At or behind the origin the closest approach is the surface
                  ;; the ray leaves (shadow-soft.glsl): no darkening.
                  (let [along (- t y)]
                    (when (> along 0)
                      (set seen (min seen (/ closest (* softness along))))))
                  (set h-prev h)
                  (set he-prev he)
                  (set t (+ t h))
                  (when (>= t limit) (set result -1))))))
        (if (= result 0) 0
            (let [s (clamp01 seen)] (* s s (- 3 (* 2 s)))))))))

(fn visibility [T plan draw]
  "How much of a light reaches a point, for `plan` (plan.lighting set) over tracer
parts `T` (its marches, distance field and hit tests; see src/reference.fnl): (fn [ox
oy oz lx ly lz reach softness]) -> 0..1, along the unit direction l from o up to
`reach`: 1 without shadows, 0 or 1 for a hard shadow, the penumbra estimate for a
soft one (softness above 0, with soft shadows on)."
  (let [march T.march
        shadows? plan.shadows?
        soft? plan.lighting.soft?
        soft-visibility (soft-visibility-fn T draw plan.lighting.shadow-steps)]
    (fn hard-visibility [ox oy oz lx ly lz reach]
      (let [ts (march ox oy oz lx ly lz reach)]
        (if (< ts reach) 0 1)))

    (fn [ox oy oz lx ly lz reach softness]
      (if (not shadows?) 1
          (and soft? (> softness 0)) (soft-visibility ox oy oz lx ly lz reach softness)
          (hard-visibility ox oy oz lx ly lz reach)))))

{: visibility}

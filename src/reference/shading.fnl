;; The CPU reference's colours: the article's classic model (Lambert, hard shadows,
;; mirror bounces), the normals, glow and heat views, and the shaded view of the
;; modern model through src/reference/lighting.fnl.

(local {: clamp01} (require :src.reference.vec))

(local sqrt math.sqrt)
(local abs math.abs)

(fn heat-color [h]
  "The heat view's colour for h (steps / max-steps, clamped to [0, 1]): r g b."
  (let [h (clamp01 h)]
    (values (clamp01 (- 1.5 (abs (- (* 4 h) 3))))
            (clamp01 (- 1.5 (abs (- (* 4 h) 2))))
            (clamp01 (- 1.5 (abs (- (* 4 h) 1)))))))

(fn lighter [ctx parts]
  "The classic model's light of a tracer's settings `ctx` over `parts` (its march,
hit tests and :bound-spheres): (fn [px py pz nx ny nz]) -> lambert, shadowed?"
  (let [{: scene : shadows? : draw : tally} ctx
        {: march : normal-delta : bound-spheres} parts
        [lx ly lz] scene.light.pos]
    (fn [px py pz nx ny nz]
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
            (values lambert false))))))

(fn object-index-fn [plan]
  (fn [i]
    (when i (. plan.objects i :index))))

(fn mirror-bouncer [ctx parts]
  "The classic model's mirror bounces of a tracer's settings `ctx` over `parts` (its
march, normals, map-color, lightness and hit tests): (fn [r g b px py pz nx ny nz dx
dy dz primary-mirror result]) -> r g b, the colour r g b seen at the surface point p
(normal n, reached along d, mirror amount primary-mirror) with its reflections,
adding each bounce's object to result.path (-1: escaped) and its point to
result.points."
  (let [{: scene : plan : draw : reflections : tally} ctx
        {: march : normal : map-color : lightness : normal-delta} parts
        [er eg eb] scene.environment
        object-index (object-index-fn plan)]
    (fn [r g b px py pz nx ny nz dx dy dz primary-mirror result]
      (var (r g b) (values r g b))
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
                (set mirror hit-mirror)))))
      (values r g b))))

(fn tracer [ctx parts]
  "The trace of a tracer's settings `ctx` (src/reference/settings.fnl) over `parts`
(its march, normals, map-color, lightness and, for the modern model's shaded view,
:modern-shade): (fn [ox oy oz dx dy dz]) -> {:color [r g b] :hit? :distance :steps
:object (scene index or nil) :shadowed? :lightness :path :points}."
  (let [{: scene : plan : view : shaded? : glow? : draw : max-steps : tally} ctx
        {: march : normal : map-color : lightness : modern-shade} parts
        [er eg eb] scene.environment
        object-index (object-index-fn plan)
        bounces (mirror-bouncer ctx parts)]
    (fn [ox oy oz dx dy dz]
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
                  ;; Then the mirror bounces.
                  (set (r g b) (bounces (* cr lambert) (* cg lambert) (* cb lambert)
                                        px py pz nx ny nz dx dy dz primary-mirror result)))
                _ (error (.. "reference: unknown view " (tostring view))))))
        (set result.color [(clamp01 r) (clamp01 g) (clamp01 b)])
        result))))

{: heat-color : lighter : tracer}

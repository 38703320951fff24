;; The CPU reference's rays: the camera's primary ray through a point of a pixel, and
;; adaptive supersampling's edge tests on a centre ray (shaders/pipeline/adaptive.glsl).

(local camera (require :src.render.camera))
(local {: normalize : safe-normalize} (require :src.reference.vec))

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

(fn edge-test [ctx parts]
  "Adaptive supersampling's edge tests (plan.edge-tests) of a tracer's settings
`ctx` over `parts` (its normals and map): (fn [ox oy oz dx dy dz t]) -> whether the
centre ray from o along d that went t needs the pixel's grid of rays."
  (let [{: plan : draw : pixel-angle} ctx
        {: normal : map} parts]
    (fn [ox oy oz dx dy dz t]
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
                  (and (< facing tests.grazing) (> turn tests.limb-turn)))))))))

{: ray-setup : edge-test}

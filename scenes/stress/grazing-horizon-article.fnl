;; Stress: grazing-horizon-down.fnl with the article's render settings (a fixed hit test
;; of 1e-4 world units, one-sided normals, no over-relaxation, 500 steps, no bounds: the
;; plane is marched, not met in closed form). Rays near the
;; horizon spend the whole step budget creeping along the plane and stop where they run
;; out, which counts as a hit (the distance is below the draw distance). Measured at
;; 96x64: 6.0% of the pixels at the step limit against 4.5% with the defaults (relative
;; hit test, over-relaxation 1.5), and the GPU still matches the reference there.
{:name "stress grazing horizon article"
 :camera {:pos [0 0 0.01] :yaw 90 :pitch 0.5 :fov 60}
 :light {:pos [-30 20 20]}
 :render {:draw-distance 100000 :hit-test :fixed :epsilon 1e-4 :normals :one-sided :normals-of :scene
          :relaxation 1 :max-steps 500 :bounds false
          :out-of-steps :surface}
 :objects [{:kind :plane :height 0 :color [0.8 0.8 0.75]}
           {:kind :sphere :radius 1 :pos [2 30 1] :color [0.8 0.3 0.2]}]}

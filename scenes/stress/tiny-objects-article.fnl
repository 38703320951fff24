;; Stress: tiny-objects.fnl with the article's render settings (a fixed hit test of 1e-4
;; world units, one-sided normals, no over-relaxation, 500 steps). The hit threshold is
;; as large as the objects, so rays stop up to 1e-4 short of them: the sphere and the
;; box swell, the ground 2e-4 below them is reached early, and one-sided normals over
;; a step of about 1e-6 are still fine but the silhouettes are wrong by a third of the
;; objects' size.
{:name "stress tiny objects article"
 :camera {:pos [0 -0.001 0.0002] :yaw 90 :pitch 35 :fov 60}
 :light {:pos [-0.003 -0.002 0.004]}
 :render {:hit-test :fixed :epsilon 1e-4 :normals :one-sided :normals-of :scene :relaxation 1 :max-steps 500
          :bounds false :out-of-steps :surface}
 :objects [{:kind :sphere :radius 0.0001 :pos [-0.00015 0 0.0001] :color [0.56 0.11 0.05]}
           {:kind :box :size [0.0001 0.0001 0.0001] :pos [0.00015 0 0.00005] :color [0.79 0.69 0.59]}
           {:kind :plane :height -0.0002 :color [0.97 0.27 0.35]}]}

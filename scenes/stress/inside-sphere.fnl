;; Stress: the camera inside a sphere (at its centre), other objects outside it. The
;; distance at the camera is negative (-4), below any hit threshold, so the march stops
;; at its first step with t = -4: a "hit" behind the camera. The image must still be
;; finite and the same on the GPU and the reference (the sphere's inside, shaded with
;; its outward normal and the light outside it).
{:name "stress inside sphere"
 :camera {:pos [0 0 2] :yaw 90 :pitch 10 :fov 60}
 :light {:pos [-30 20 20]}
 :objects [{:kind :sphere :radius 4 :pos [0 0 2] :color [0.56 0.11 0.05]}
           {:kind :box :size [2 2 2] :pos [0 8 1] :color [0.79 0.69 0.59]}
           {:kind :plane :height 0 :color [0.97 0.27 0.35]}]}

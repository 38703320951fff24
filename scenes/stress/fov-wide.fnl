;; Stress: a field of view of 179 degrees: the projection distance is 0.0087, so the
;; image's edge rays point almost sideways (and, with the wide aspect, behind the
;; camera's plane); forward contributes little to each ray and its rounding shows.
{:name "stress fov wide"
 :camera {:pos [0 -4 2] :yaw 90 :pitch 10 :fov 179}
 :light {:pos [-30 -20 20]}
 :objects [{:kind :sphere :radius 1 :pos [0 0 1] :color [0.56 0.11 0.05]}
           {:kind :box :size [2 2 2] :pos [-4 -4 1] :color [0.79 0.69 0.59]}
           {:kind :plane :height 0 :color [0.97 0.27 0.35]}]}

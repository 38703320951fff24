;; Stress: a draw distance (1) smaller than the nearest object (the ground, 3 below the
;; camera; the rest further). The distance estimator starts from the draw distance, so
;; every ray's first step is the full draw distance and ends the march: the whole image
;; is sky, in one step, with no object code reached.
{:name "stress draw distance short"
 :camera {:pos [0 -8 3] :yaw 90 :pitch 15 :fov 60}
 :light {:pos [-30 -20 20]}
 :render {:draw-distance 1}
 :objects [{:kind :sphere :radius 1 :pos [1 0 1] :color [0.56 0.11 0.05]}
           {:kind :box :size [1.5 1.5 1.5] :pos [-1.5 1 0.75] :color [0.79 0.69 0.59]}
           {:kind :plane :height 0 :color [0.97 0.27 0.35]}]}

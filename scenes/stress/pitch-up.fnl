;; Stress: pitch -90, looking straight up from the ground at a sphere and a box hanging
;; above, the sky behind them. As pitch-down.fnl: the article's camera basis is 0/0
;; for an exactly vertical forward; the yaw-built basis is finite.
{:name "stress pitch up"
 :camera {:pos [0 0 0.5] :yaw 90 :pitch -90 :fov 60}
 :light {:pos [-30 20 -20]}
 :objects [{:kind :box :size [2 2 1] :pos [-1.5 0.5 6] :color [0.79 0.69 0.59]}
           {:kind :sphere :radius 1 :pos [1.5 -0.5 5] :color [0.56 0.11 0.05]}
           {:kind :plane :height 0 :color [0.97 0.27 0.35]}]}

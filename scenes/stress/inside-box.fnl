;; Stress: the camera inside a box (off centre), other objects outside it. The box's
;; exact signed distance is negative inside, so the first step is already a hit at a
;; negative distance, and the normals there come from the interior distance, whose
;; gradient jumps across the box's inner diagonals (the article's unsigned box was 0
;; inside and gave no normal at all).
{:name "stress inside box"
 :camera {:pos [0.5 -0.3 1.2] :yaw 80 :pitch 10 :fov 60}
 :light {:pos [-30 20 20]}
 :objects [{:kind :box :size [4 4 3] :pos [0 0 1.5] :color [0.79 0.69 0.59]}
           {:kind :sphere :radius 1 :pos [0 8 1] :color [0.56 0.11 0.05]}
           {:kind :plane :height 0 :color [0.97 0.27 0.35]}]}

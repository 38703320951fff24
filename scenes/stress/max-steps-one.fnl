;; Stress: a step budget of one. Every ray takes a single step of the distance at the
;; camera and stops there; as that is below the draw distance it counts as a hit, at a
;; point in mid-air, shaded with the colour of whatever is nearest. Nonsense, but the
;; same nonsense on the GPU and the reference, and the heat view must read exactly 1.
;; (:out-of-steps :surface keeps the article's shading of rays out of steps, which this
;; scene is about; the default would show them the background.)
{:name "stress max steps one"
 :camera {:pos [0 -8 3] :yaw 90 :pitch 15 :fov 60}
 :light {:pos [-30 -20 20]}
 :render {:max-steps 1 :out-of-steps :surface}
 :objects [{:kind :sphere :radius 1 :pos [1 0 1] :color [0.56 0.11 0.05]}
           {:kind :box :size [1.5 1.5 1.5] :pos [-1.5 1 0.75] :color [0.79 0.69 0.59]}
           {:kind :plane :height 0 :color [0.97 0.27 0.35]}]}

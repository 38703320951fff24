;; Stress: pitch +90, looking straight down at the ground. The article's camera takes
;; right = normalize(cross([0 0 -1], forward)), 0/0 for an exactly vertical forward:
;; a NaN image (in float32 always; in double only cos(90 degrees) = 6e-17 saves it).
;; The basis is built from the yaw instead, so the image is finite and turns with yaw.
{:name "stress pitch down"
 :camera {:pos [0 0 6] :yaw 90 :pitch 90 :fov 60}
 :light {:pos [-30 20 20]}
 :objects [{:kind :box :size [2 2 2] :pos [-1.5 0.5 1] :color [0.79 0.69 0.59]}
           {:kind :sphere :radius 1 :pos [1.5 -0.5 1] :color [0.56 0.11 0.05]}
           {:kind :plane :height 0 :color [0.97 0.27 0.35]}]}

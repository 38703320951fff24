;; Stress: a field of view of 1 degree (a telephoto): the projection distance is 115,
;; neighbouring rays differ by about 3e-4 degrees, and the scene is 60 units away.
;; Float32 ray directions are that close to each other's rounding, and edges must
;; still land on the same pixels as in double.
{:name "stress fov narrow"
 :camera {:pos [0 -60 2] :yaw 90 :pitch 0 :fov 1}
 :light {:pos [-30 -20 20]}
 :objects [{:kind :sphere :radius 0.3 :pos [0 0 2] :color [0.56 0.11 0.05]}
           {:kind :box :size [0.2 0.2 0.2] :pos [0.35 -0.5 2.1] :color [0.79 0.69 0.59]}
           {:kind :plane :height 0 :color [0.97 0.27 0.35]}]}

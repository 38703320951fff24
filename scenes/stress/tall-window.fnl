;; Stress: a 1 x 1000 window (the spec renders this scene at :size [1 1000]): the
;; aspect ratio is 0.001, so uv x is always about 0 and every pixel's ray lies in the
;; vertical plane through the view direction; pixel centres and the y flip between the
;; GPU (gl_FragCoord grows upwards) and the reference must line up row by row.
{:name "stress tall window"
 :camera {:pos [0 -8 3] :yaw 90 :pitch 10 :fov 60}
 :light {:pos [-30 -20 20]}
 :objects [{:kind :sphere :radius 1 :pos [0 0 1] :color [0.56 0.11 0.05]}
           {:kind :box :size [1 1 1] :pos [0 2 2.5] :color [0.79 0.69 0.59]}
           {:kind :plane :height 0 :color [0.97 0.27 0.35]}]}

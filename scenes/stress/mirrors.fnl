;; Stress: two parallel mirrors (boxes facing each other 6 units apart) with the camera
;; between them and 10 mirror bounces, so most rays bounce back and forth to the end
;; of the budget. Each bounce starts off the surface by twice the normal step and takes
;; the normal by finite differences: any error in either compounds over 10 bounces,
;; and a ray offset that is too small restarts the march on the surface (a zero-length
;; bounce, the same point hit again).
{:name "stress mirrors"
 :camera {:pos [0 0 2] :yaw 80 :pitch 5 :fov 60}
 :light {:pos [0 0 8]}
 :render {:reflections 10}
 :objects [{:kind :box :size [20 0.5 10] :pos [0 -3.25 3] :color [0.7 0.75 0.8]}
           {:kind :box :size [20 0.5 10] :pos [0 3.25 3] :color [0.8 0.75 0.7]}
           {:kind :sphere :radius 0.7 :pos [1.5 1 1.5] :color [0.56 0.11 0.05]}
           {:kind :plane :height 0 :color [0.97 0.27 0.35]}]}

;; Stress: the light exactly on surfaces: on the ground plane (z = 0) and on a sphere's
;; top. A hit point can coincide with the light, where the direction to it is 0/0
;; (the renderer lights such a point along its normal instead of returning NaN); the
;; ground around it is lit edge-on (Lambert 0), and shadow rays toward the light
;; leave from points grazing the surface.
{:name "stress light on surface"
 :camera {:pos [0 -6 3] :yaw 90 :pitch 30 :fov 60}
 :light {:pos [0 0 0]}
 :objects [{:kind :sphere :radius 1 :pos [1.5 1 1] :color [0.56 0.11 0.05]}
           {:kind :box :size [1 1 1] :pos [-1.5 0.5 0.5] :color [0.79 0.69 0.59]}
           {:kind :plane :height 0 :color [0.97 0.27 0.35]}]}

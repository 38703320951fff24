;; Stress: the light inside an object (at the centre of a sphere). The sphere is lit
;; from inside, so its outside faces away from the light (Lambert 0); every shadow ray
;; from the rest of the scene ends in the sphere, so everything else is in shadow.
;; Shadow marches toward a light inside a solid must stop at its surface, not run on.
{:name "stress light inside"
 :camera {:pos [0 -8 3] :yaw 90 :pitch 15 :fov 60}
 :light {:pos [0 0 1.5]}
 :objects [{:kind :sphere :radius 1.5 :pos [0 0 1.5] :color [0.56 0.11 0.05]}
           {:kind :box :size [1 1 1] :pos [2.5 1 0.5] :color [0.79 0.69 0.59]}
           {:kind :plane :height 0 :color [0.97 0.27 0.35]}]}

;; Stress: coincident surfaces. Two identical boxes in different colours, and a plane
;; at the height of another box's top face. Their distances tie exactly, so the colour
;; is decided by the tie-break (the first object in plan order wins, on the GPU and in
;; the reference alike); a renderer whose tie depends on rounding shows z-fighting
;; speckle that moves with the camera.
{:name "stress coincident"
 :camera {:pos [6 -7 4] :yaw 130 :pitch 25 :fov 60}
 :light {:pos [-30 -20 20]}
 :objects [{:kind :box :size [2 2 2] :pos [0 0 1] :color [0.8 0.2 0.2]}
           {:kind :box :size [2 2 2] :pos [0 0 1] :color [0.2 0.2 0.8]}
           {:kind :box :size [3 2 1] :pos [-2 3 -0.5] :color [0.2 0.7 0.3]}
           {:kind :plane :height 0 :color [0.97 0.8 0.35]}]}

;; Stress: the camera 1e5 units from the origin (on every axis) looking at unit-sized
;; objects a few units away; everything, light and ground included, is offset by 1e5.
;; In float32 1e5 has a spacing of about 0.008, so a shader that got world positions
;; and subtracted the camera itself would see the objects snap to a coarse grid and
;; their normals fall apart. Positions are sent camera-relative, subtracted on the CPU
;; in double, so this scene must look like the same scene at the origin.
{:name "stress far origin"
 :camera {:pos [100000 99990 100003] :yaw 90 :pitch 15 :fov 60}
 :light {:pos [99970 100020 100020]}
 :objects [{:kind :box :size [2 2 2] :pos [99998.5 100000 100001] :color [0.79 0.69 0.59]}
           {:kind :sphere :radius 1 :pos [100001.5 100000 100001] :color [0.56 0.11 0.05]}
           {:kind :sphere :radius 0.5 :pos [100000 99997 100000.5] :color [0.2 0.45 0.85]}
           {:kind :plane :height 100000 :color [0.97 0.27 0.35]}]}

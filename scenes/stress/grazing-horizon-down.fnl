;; Stress: the grazing ground plane of grazing-horizon.fnl with the camera pitched
;; slightly down (0.5 degrees), so the horizon sits just above the middle of the image
;; and the rows under it hit the plane at a few degrees or less: long, slow marches
;; whose hit points float32 can only place to a few ulps of a large t, and shadow rays
;; that leave the ground at a grazing angle toward a low light. A fixed hit test of
;; 1e-4 world units is finer than float32's spacing beyond t = 2048 (0.008 at 1e5), so
;; distant rays cannot meet it; the relative hit test scales with t.
{:name "stress grazing horizon down"
 :camera {:pos [0 0 0.01] :yaw 90 :pitch 0.5 :fov 60}
 :light {:pos [-30 20 20]}
 :render {:draw-distance 100000}
 :objects [{:kind :plane :height 0 :color [0.8 0.8 0.75]}
           {:kind :sphere :radius 1 :pos [2 30 1] :color [0.8 0.3 0.2]}]}

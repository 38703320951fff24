;; Stress: a ground plane seen at grazing angles, the camera 0.01 above it looking level
;; at the horizon, with a long draw distance. Near the horizon every ray runs almost
;; parallel to the plane, so its distance bound (the camera's height over the ground)
;; is tiny and the march crawls: the rows just under the horizon spend the whole step
;; budget and stop short of the ground, which still counts as a hit (the distance is
;; below the draw distance), so where the ground ends depends on float32 rounding over
;; hundreds of steps. A hit test relative to the distance travelled and over-relaxation
;; (the defaults) let more of them arrive; see grazing-horizon-article.fnl for the
;; article's settings (the spec prints the share of pixels at the step limit).
{:name "stress grazing horizon"
 :camera {:pos [0 0 0.01] :yaw 90 :pitch 0 :fov 60}
 :light {:pos [-30 20 20]}
 :render {:draw-distance 100000}
 :objects [{:kind :plane :height 0 :color [0.8 0.8 0.75]}
           {:kind :sphere :radius 1 :pos [2 30 1] :color [0.8 0.3 0.2]}]}

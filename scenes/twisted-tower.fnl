;; A twisted tower: a hexagonal shaft and a box core twisted about the vertical axis
;; (their Lipschitz factors make the marcher take shorter steps), a stretched
;; octahedron crown, stairs-union terraces at the foot, and a bent bridge beside it.
{:name "twisted tower"
 :camera {:pos [18 -21 8] :yaw 130 :pitch 0 :fov 55}
 :light {:pos [25 -20 40]}
 :environment [0.55 0.62 0.75]
 ;; The modern look (see docs/scenes.md, Lighting); m in the player shows the classic model.
 :lighting {:lights [{:kind :sun :direction [-0.6 -0.45 0.65] :color [1 0.9 0.75]
                      :intensity 3 :softness 0.03}]
            :sky-zenith [0.25 0.4 0.75] :sky-horizon [0.7 0.75 0.85]
            :ambient 0.45 :ao 0.7 :ao-radius 1 :fog 0.002 :fog-color [0.7 0.75 0.85]
            :exposure 1.1}
 :render {:reflections 1 :draw-distance 300}
 :objects
 [{:kind :plane :height 0 :color [0.45 0.5 0.42]}
  {:kind :stairs-union :radius 0.9 :steps 4 :color [0.8 0.78 0.74] :mirror 0
   :children [{:kind :box :size [7 7 0.6] :pos [0 0 0.3]}
              {:kind :twist :angle 22 :pos [0 0 4.6]
               :children [{:kind :hex-prism :radius 1.3 :height 8}]}]}
  {:kind :twist :angle -30 :pos [0 0 4.6] :color [0.85 0.35 0.25] :mirror 0.2
   :children [{:kind :box :size [0.9 3.2 7.6]}]}
  {:kind :stretch :factors [1 1 2.2] :pos [0 0 9.9] :color [0.95 0.8 0.3] :mirror 0.5
   :children [{:kind :octahedron :size 1.2}]}
  ;; A bridge bent into an arc.
  {:kind :bend :angle -14 :pos [6 -1 1.8] :color [0.5 0.55 0.65] :mirror 0
   :children [{:kind :round-box :size [6 1.2 0.3] :radius 0.1}]}]}

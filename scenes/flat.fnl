;; No reflections and no shadows: the shader has neither a bounce loop nor a shadow
;; march, only primary rays and the Lambert term.
{:name "flat"
 :camera {:pos [14 -14 9] :yaw 135 :pitch 25 :fov 55}
 :light {:pos [10 -20 30]}
 :environment [0.85 0.9 0.95]
 :render {:reflections 0 :shadows false :max-steps 300 :draw-distance 200}
 :objects [{:kind :box :size [4 4 4] :pos [0 0 2] :color [0.9 0.55 0.2]}
           {:kind :box :size [8 1 1] :pos [0 4 0.5] :color [0.3 0.6 0.9]}
           {:kind :sphere :radius 1.5 :pos [-4 -2 1.5] :color [0.3 0.8 0.4]}
           {:kind :sphere :radius 1 :pos [4 -3 1] :color [0.8 0.2 0.5]}
           {:kind :plane :height 0 :color [0.8 0.8 0.75]}]}

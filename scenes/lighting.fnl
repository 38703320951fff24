;; The modern lighting model (a :lighting section): a low warm sun with soft shadows,
;; a blue point light, a sky with a sun disc, ambient occlusion, a little fog, and
;; materials that differ in colour, mirror amount, roughness and emission. Press m in
;; the player to switch to the article's classic model and back: the same objects,
;; Lambert light, hard shadows that halve it, every surface a mirror.
{:name "lighting"
 :camera {:pos [9 -11 4.5] :yaw 128 :pitch 14 :fov 55}
 :light {:pos [-20 -14 18]}
 :lighting {:lights [{:kind :sun :direction [-0.55 -0.45 0.45] :color [1 0.85 0.65]
                      :intensity 3 :softness 0.06}
                     {:kind :point :pos [2.5 3 2.5] :color [0.45 0.65 1] :intensity 3
                      :range 3}]
            :sky-zenith [0.25 0.45 0.8] :sky-horizon [0.85 0.8 0.75]
            :ambient 0.45 :ao 0.9 :ao-radius 0.6
            :fog 0.012 :fog-color [0.8 0.78 0.74] :exposure 1.1}
 :render {:reflections 2 :draw-distance 400}
 :objects
 [{:kind :plane :height 0 :color [0.62 0.6 0.56]}
  ;; A chrome ball, a rough clay ball and a glossy plastic one.
  {:kind :sphere :radius 1.2 :pos [0 0 1.2] :color [0.92 0.92 0.95] :mirror 1 :roughness 0.02}
  {:kind :sphere :radius 1 :pos [-2.6 1.2 1] :color [0.8 0.35 0.2] :roughness 0.9}
  {:kind :sphere :radius 0.8 :pos [2.4 -1.4 0.8] :color [0.15 0.35 0.75] :roughness 0.15}
  ;; A stepped plinth, its steps melted together.
  {:kind :smooth-union :radius 0.15 :pos [-1 4.5 0] :color [0.85 0.82 0.75] :roughness 0.6
   :children [{:kind :box :size [3 3 0.6] :pos [0 0 0.3]}
              {:kind :box :size [2 2 0.6] :pos [0 0 0.9]}
              {:kind :box :size [1 1 1.4] :pos [0 0 1.9]}]}
  ;; A glowing lamp on the plinth, and a gold torus beside it.
  {:kind :sphere :radius 0.35 :pos [-1 4.5 2.95] :color [1 0.75 0.4] :emission 4}
  {:kind :torus :radius 0.7 :thickness 0.2 :pos [1.6 2.2 0.2]
   :color [1 0.78 0.35] :mirror 0.85 :roughness 0.2}]}

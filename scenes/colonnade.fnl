;; An endless colonnade: columns repeated forever along x (each a fluted shaft, a
;; rounded base and a capital), a limited row of arches overhead, a floor of tiles
;; repeated in both directions, and a hollow (onion) dome at the end of the view.
(local marble [0.9 0.88 0.82])

{:name "colonnade"
 :camera {:pos [-2 -5.5 2.2] :yaw 35 :pitch 3 :fov 65}
 :light {:pos [-20 -30 40]}
 :environment [0.98 0.85 0.65]
 ;; The modern look (see docs/scenes.md, Lighting); m in the player shows the classic model.
 :lighting {:lights [{:kind :sun :direction [-0.45 -0.6 0.55] :color [1 0.82 0.6]
                      :intensity 3.2 :softness 0.04}]
            :sky-zenith [0.35 0.5 0.8] :sky-horizon [0.98 0.85 0.65]
            :ambient 0.45 :ao 0.8 :ao-radius 0.5
            :fog 0.015 :fog-color [0.98 0.85 0.65] :exposure 1.1}
 :render {:reflections 1 :draw-distance 300}
 :objects
 [{:kind :plane :height -0.05 :color [0.3 0.28 0.26]}
  ;; Floor tiles: rounded boxes repeated in x and y.
  {:kind :repeat :period [2 2 0] :color [0.72 0.68 0.6] :mirror 0.3
   :children [{:kind :round-box :size [1.9 1.9 0.1] :radius 0.03}]}
  ;; Two rows of columns, infinite along x.
  {:kind :repeat :period [4 0 0] :color marble :mirror 0.1
   :children
   [{:kind :mirror :normal [0 1 0]
     :children
     [{:kind :union :pos [0 2 0]
       :children [{:kind :rounded-cylinder :radius 0.5 :height 0.3 :rounding 0.05 :pos [0 0 0.15]}
                  ;; The shaft less its twelve flutes (a polar repetition of one).
                  {:kind :subtraction
                   :children [{:kind :capped-cylinder :radius 0.34 :height 3.6 :pos [0 0 2.1]}
                              {:kind :polar :count 12
                               :children [{:kind :capped-cylinder :radius 0.06 :height 3.4
                                           :pos [0.36 0 2.1]}]}]}
                  {:kind :capped-cone :height 0.3 :radius1 0.36 :radius2 0.5 :pos [0 0 4.05]}
                  {:kind :box :size [1.1 1.1 0.2] :pos [0 0 4.3]}]}]}]}
  ;; Arches over the aisle, a limited repetition of 7 (count 3 each side).
  {:kind :repeat :period [4 0 0] :count [3 0 0] :color [0.85 0.8 0.72]
   :children [{:kind :subtraction :pos [0 0 4.9]
               :children [{:kind :box :size [0.6 4.8 1]}
                          {:kind :capped-cylinder :radius 1.7 :height 1 :rotate [0 90 0] :pos [0 0 -1.3]}]}]}
  ;; A hollow dome far down the aisle, cut open to show its shell.
  {:kind :intersection :pos [30 0 0] :color [0.55 0.65 0.8] :mirror 0
   :children [{:kind :onion :thickness 0.15
               :children [{:kind :onion :thickness 0.3 :children [{:kind :sphere :radius 4}]}]}
              {:kind :plane :normal [0 -1 0] :height 0.5}]}]}

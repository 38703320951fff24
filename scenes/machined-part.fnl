;; A machined bracket on a workbench: a chamfered block with drilled holes (capped
;; cylinders subtracted, the cut shows the drill's colour), a bolted hexagon nut, a
;; rounded flange, a box frame guard and a link chain. Subtraction, chamfer union,
;; round-box, box-frame, hex-prism, link, onion tubing and elongation.
(local steel [0.62 0.64 0.68])
(local brass [0.78 0.6 0.25])

(local holes
  (icollect [_ x (ipairs [-1.6 0 1.6])]
    {:kind :capped-cylinder :radius 0.35 :height 3 :pos [x 0 0] :color [0.2 0.2 0.22]}))

{:name "machined part"
 :camera {:pos [6.5 -7 5] :yaw 133 :pitch 28 :fov 55}
 :light {:pos [10 -14 22]}
 :environment [0.78 0.82 0.88]
 ;; The modern look (see docs/scenes.md, Lighting); m in the player shows the classic model.
 :lighting {:lights [{:kind :sun :direction [0.4 -0.55 0.75] :intensity 3 :softness 0.03}
                     {:kind :point :pos [-2 -4 3] :color [1 0.8 0.6] :intensity 1.5 :range 4}]
            :sky-zenith [0.45 0.55 0.7] :sky-horizon [0.8 0.82 0.86]
            :ambient 0.55 :ao 0.8 :ao-radius 0.3 :exposure 1.1}
 :render {:reflections 1 :draw-distance 200}
 :objects
 [{:kind :plane :height 0 :color [0.42 0.34 0.27]}
  ;; The bracket: a block and an upright joined by a chamfer, drilled through.
  {:kind :subtraction :color steel :mirror 0.25
   :children [{:kind :chamfer-union :radius 0.5
               :children [{:kind :box :size [5 2 0.8] :pos [0 0 0.4]}
                          {:kind :round-box :size [5 0.6 2.6] :radius 0.08 :pos [0 0.7 1.3]}]}
              {:kind :union :children holes}
              {:kind :capped-cylinder :radius 0.3 :height 2 :rotate [90 0 0] :pos [-1.6 0.7 1.8]
               :color [0.2 0.2 0.22]}
              {:kind :capped-cylinder :radius 0.3 :height 2 :rotate [90 0 0] :pos [1.6 0.7 1.8]
               :color [0.2 0.2 0.22]}]}
  ;; A nut on the middle hole.
  {:kind :subtraction :pos [0 0 0.95] :color brass :mirror 0.4
   :children [{:kind :hex-prism :radius 0.55 :height 0.3 :rotate [0 0 30]}
              {:kind :capped-cylinder :radius 0.33 :height 1}]}
  ;; A flange: a rounded cylinder with an elongated slot cut in it.
  {:kind :subtraction :pos [3.6 -2.2 0.25] :color [0.35 0.45 0.6]
   :children [{:kind :rounded-cylinder :radius 1 :height 0.5 :rounding 0.08}
              {:kind :elongate :size [0.8 0 0]
               :children [{:kind :capped-cylinder :radius 0.2 :height 1}]}]}
  ;; A wire guard.
  {:kind :box-frame :size [1.6 1.6 1.6] :thickness 0.08 :pos [-3.8 -2 0.8]
   :color [0.9 0.75 0.1] :mirror 0}
  ;; Tubing: a hollow pipe (onion of a capsule), cut open so its wall shows.
  {:kind :intersection :color [0.2 0.55 0.3] :mirror 0
   :children [{:kind :onion :thickness 0.06
               :children [{:kind :capsule :a [-1.5 0 0] :b [1.5 0 0] :radius 0.3}]}
              {:kind :plane :normal [0 0 1] :height 0}]
   :pos [0 -2.6 0.3]}
  ;; A chain of links.
  {:kind :union :color [0.55 0.55 0.58]
   :children (fcollect [i 0 3]
               {:kind :link :length 0.4 :radius 0.3 :thickness 0.07
                :rotate [(if (= (% i 2) 0) 0 90) 0 0] :pos [(+ -1.2 (* i 0.78)) -4.2 0.37]})}]}

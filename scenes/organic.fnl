;; A smooth-blended creature on a pebble beach: a body of ellipsoids and capsules
;; melted together with polynomial and exponential smooth unions (the materials blend
;; with the distances), round-cone legs, a vesica beak, eyes cut with a smooth
;; subtraction, a displaced rock and a smooth-intersection lens.
;; Four values are parameters: F2 in the player shows a panel to change them live and
;; save them back into this file.
(local skin (param :skin [0.85 0.45 0.35]))

(local legs
  (icollect [_ [x y] (ipairs [[-0.7 -0.5] [-0.7 0.5] [0.7 -0.5] [0.7 0.5]])]
    {:kind :round-cone :radius1 0.18 :radius2 0.28 :height 1 :pos [x y 0.68]}))

{:name "organic"
 :camera {:pos [5.5 -6 3.2] :yaw 131 :pitch 12 :fov 50}
 :light {:pos [12 -16 25]}
 :environment [0.62 0.75 0.92]
 ;; The modern look (see docs/scenes.md, Lighting); m in the player shows the classic model.
 :lighting {:sky-zenith [0.3 0.5 0.85] :sky-horizon [0.75 0.82 0.92]
            :ambient 0.5 :ao 0.9 :ao-radius 0.4 :exposure 1.1}
 :render {:reflections 1 :draw-distance 200 :shadows (param :shadows true)}
 :objects
 [{:kind :plane :height 0 :color [0.85 0.8 0.68]}
  {:kind :smooth-subtraction :radius 0.08 :color skin :mirror 0.15
   :children
   [{:kind :smooth-union :radius (param :melt 0.35 {:min 0.01 :max 0.8})
     :children [{:kind :ellipsoid :radii [1.3 0.8 0.7] :pos [0 0 1.5]}
                {:kind :smooth-union :radius 0.25 :kernel :exp
                 :children [{:kind :sphere :radius 0.55 :pos [1.55 0 2.25]}
                            {:kind :capsule :a [0.9 0 1.8] :b [1.4 0 2.15] :radius 0.3}]}
                {:kind :union :children legs}
                {:kind :capsule :a [-1.2 0 1.6] :b [-2 0 2.3] :radius 0.12 :color [0.95 0.7 0.3]}
                {:kind :vesica :length 0.6 :width 0.22 :rotate [0 90 0] :pos [2.15 0 2.2]
                 :color [0.95 0.8 0.2]}]}
    {:kind :sphere :radius 0.12 :pos [1.92 -0.3 2.42] :color [0.05 0.05 0.08]}
    {:kind :sphere :radius 0.12 :pos [1.92 0.3 2.42] :color [0.05 0.05 0.08]}]}
  ;; A rock whose surface is displaced by a smooth wave.
  {:kind :displace :amplitude (param :bumps 0.06 {:min 0 :max 0.12}) :frequency 9 :pos [-2.2 -2 0.3] :color [0.45 0.47 0.5] :mirror 0
   :children [{:kind :ellipsoid :radii [0.9 0.7 0.55]}]}
  ;; A lens: two spheres' smooth intersection, glassy (a full mirror).
  {:kind :smooth-intersection :radius 0.1 :pos [0.5 -2.4 0.6] :color [0.6 0.8 0.95]
   :children [{:kind :sphere :radius 1 :pos [0 0 -0.7]}
              {:kind :sphere :radius 1 :pos [0 0 0.7]}]}]}

;; A test scene for tools/check-states.sh, which puts test/states/hue-colours.fnl
;; (the :hue parameter, its colour `c` and sky, the view) before it: every surface and
;; the sky are one hue. Twisted, blended objects make a frame slow on llvmpipe (well
;; over the player's 0.1 s budget at 1280x720), so the player draws it in bands.
{:name "states: hue"
 :camera camera :light light :environment sky
 :render {:reflections 0 :draw-distance 200}
 :objects
 [{:kind :plane :height 0 :color c :mirror 0}
  {:kind :smooth-union :radius 0.6 :color c :mirror 0
   :children [{:kind :twist :angle 40 :pos [-2 0 2.5]
               :children [{:kind :box :size [1.2 2.4 5]}]}
              {:kind :twist :angle -35 :pos [2 0 2.5]
               :children [{:kind :hex-prism :radius 1 :height 5}]}
              {:kind :torus :radius 2.2 :thickness 0.35 :pos [0 0 1]}]}
  {:kind :displace :amplitude 0.08 :frequency 6 :pos [0 -3.5 1] :color c :mirror 0
   :children [{:kind :ellipsoid :radii [1.4 1 0.9]}]}]}

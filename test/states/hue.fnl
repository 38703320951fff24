;; A test scene for tools/check-states.sh: the hue of everything (floor, objects and
;; sky) is one colour taken from the parameter :hue (0 to 1 maps to 0 to 240 degrees,
;; red to blue), so the state a picture shows can be read from any part of it. The
;; classic lighting model with no mirrors only scales the colour's brightness (light,
;; shadow), never its hue. Twisted, blended objects make a frame slow on llvmpipe
;; (well over the player's 0.1 s budget at 1280x720), so the player draws it in bands.
(local hue (param :hue 0.1 {:min 0 :max 1}))

(fn colour [h]
  ;; Fully saturated colour of hue h (0 to 1 over 0 to 240 degrees).
  (let [d (* 240 h)
        f (fn [n] (let [k (% (+ n (/ d 60)) 6)]
                    (- 1 (math.max 0 (math.min k (- 4 k) 1)))))]
    [(f 5) (f 3) (f 1)]))

;; tools/check-states.sh plays this scene animated by writing a function of time in
;; place of the :hue line above: the colours are then functions of time too.
(fn of-hue [f]
  (if (= :function (type hue)) (fn [t] (f (hue t))) (f hue)))
(local c (of-hue colour))
(local sky (of-hue (fn [h] (icollect [_ x (ipairs (colour h))] (+ 0.45 (* 0.55 x))))))

{:name "states: hue"
 :camera {:pos [9 -10 7] :yaw 132 :pitch 22 :fov 60}
 :light {:pos [12 -16 25]}
 :environment sky
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

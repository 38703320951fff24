;; test/states/hue.fnl animated: the hue of everything is a function of time, going
;; from 24 to 216 degrees and back every 8 seconds (0.1 to 0.9 of the :hue range of
;; hue.fnl, so tools/check-states.fnl reads it the same way), 48 degrees a second.
;; A picture drawn from two moments 0.125 s apart mixes states that differ by 6
;; degrees, the classifier's tolerance.

(fn colour [h]
  ;; Fully saturated colour of hue h (0 to 1 over 0 to 240 degrees).
  (let [d (* 240 h)
        f (fn [n] (let [k (% (+ n (/ d 60)) 6)]
                    (- 1 (math.max 0 (math.min k (- 4 k) 1)))))]
    [(f 5) (f 3) (f 1)]))

(fn hue-at [t]
  ;; A triangle wave: 0.1 at t = 0, 0.9 at t = 4, 0.1 again at t = 8.
  (let [p (% (/ t 8) 1)]
    (+ 0.1 (* 0.8 (if (< p 0.5) (* 2 p) (- 2 (* 2 p)))))))

(fn c [t] (colour (hue-at t)))
(fn sky [t] (icollect [_ x (ipairs (c t))] (+ 0.45 (* 0.55 x))))

{:name "states: hue, animated"
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

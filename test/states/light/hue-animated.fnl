;; test/states/hue-animated.fnl made light (see light/hue.fnl): its hue is the same
;; function of time, 24 to 216 degrees and back every 8 seconds.

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
 :render {:reflections 0 :draw-distance 200 :shadows false}
 :objects
 [{:kind :sphere :radius 1.5 :pos [0 -3.5 1.5] :color c}
  {:kind :plane :height 0 :color c}]}

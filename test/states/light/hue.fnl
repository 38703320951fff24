;; test/states/hue.fnl made light: a sphere on the floor, no shadows, the same :hue
;; parameter and colours. A frame takes about 20-25 ms at 1280x720 on llvmpipe, under
;; the player's 25 ms for drawing the image whole in one frame (src/app/progress.fnl),
;; so even a player that refines in bands shows every picture whole:
;; `SCENES=test/states/light tools/check-states.sh` shows that the check passes then.
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
 :render {:reflections 0 :draw-distance 200 :shadows false}
 :objects
 [{:kind :sphere :radius 1.5 :pos [0 -3.5 1.5] :color c}
  {:kind :plane :height 0 :color c}]}

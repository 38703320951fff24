;; The head of every test/states scene: tools/check-states.sh puts this file before
;; the folder's hue.fnl (SCENES=test/states/light: test/states/light/hue.fnl) and plays
;; the two as one scene file (a scene file cannot load another: docs/scenes.md). The
;; hue of everything (floor, objects and sky) is one colour taken from the parameter
;; :hue (0 to 1 maps to 0 to 240 degrees, red to blue), so the state a picture shows
;; can be read from any part of it. The classic lighting model with no mirrors only
;; scales the colour's brightness (light, shadow), never its hue.
(local hue (param :hue 0.1 {:min 0 :max 1}))

(fn colour [h]
  ;; Fully saturated colour of hue h (0 to 1 over 0 to 240 degrees).
  (let [d (* 240 h)
        f (fn [n] (let [k (% (+ n (/ d 60)) 6)]
                    (- 1 (math.max 0 (math.min k (- 4 k) 1)))))]
    [(f 5) (f 3) (f 1)]))

;; tools/check-states.sh plays the scene animated by writing a function of time in
;; place of the :hue line above: the colours are then functions of time too.
(fn of-hue [f]
  (if (= :function (type hue)) (fn [t] (f (hue t))) (f hue)))
(local c (of-hue colour))
(local sky (of-hue (fn [h] (icollect [_ x (ipairs (colour h))] (+ 0.45 (* 0.55 x))))))

;; Every scene's view (`:camera camera :light light :environment sky`).
(local camera {:pos [9 -10 7] :yaw 132 :pitch 22 :fov 60})
(local light {:pos [12 -16 25]})

;; The folder's hue.fnl follows: its objects, coloured `c`, and the scene's table.

;; A test scene for tools/check-states.sh (SCENES=test/states/field): test/states/hue.fnl's
;; hue machinery over a field of marched members (issue 29): 60 rotated tori and 40
;; capsules, each placed and coloured alone, so the field holds them and their colour
;; lives in its objects texture (a value edit uploads the texels it changed; a
;; function of time changes them every frame). The hue of everything (floor, objects
;; and sky) is one colour taken from the parameter :hue (0 to 1 maps to 0 to 240
;; degrees, red to blue), so the state a picture shows can be read from any part of
;; it. The classic lighting model with no reflections only scales the colour's
;; brightness (light, shadow), never its hue.
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

(var seed 5)
(fn rnd [] (set seed (% (+ (* seed 1103515245) 12345) 2147483648)) (/ seed 2147483648))

(local tori (fcollect [_ 1 60]
              {:kind :torus :radius 0.5 :thickness 0.15 :color c
               :pos [(- (* 16 (rnd)) 8) (- (* 16 (rnd)) 8) 0.6] :rotate [(* 90 (rnd)) 0 (* 90 (rnd))]}))
(local capsules (fcollect [_ 1 40]
                  {:kind :capsule :a [-0.4 0 0] :b [0.4 0 0.2] :radius 0.2 :color c
                   :pos [(- (* 16 (rnd)) 8) (- (* 16 (rnd)) 8) (+ 0.4 (* 2 (rnd)))]
                   :rotate [0 0 (* 180 (rnd))]}))

(local members tori)
(each [_ o (ipairs capsules)] (table.insert members o))

{:name "states: hue over a field of marched members"
 :camera {:pos [9 -10 7] :yaw 132 :pitch 22 :fov 60}
 :light {:pos [12 -16 25]}
 :environment sky
 :render {:reflections 0 :draw-distance 200}
 :objects
 [{:kind :plane :height 0 :color c :mirror 0}
  (table.unpack members)]}

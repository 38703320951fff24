;; Functions of time, an animated light: a sundial on a terrace through a day. The sun
;; rises, crosses the sky and sets every 24 s (its direction, colour and intensity are
;; functions of the time in seconds), warm and low at the ends of the day, so the
;; gnomon's and the pillars' shadows sweep the dial and the floor and the sky turns
;; from dusk to noon and back. See docs/scenes.md, Functions of time. Space pauses
;; and plays in the player, `.` steps a frame;
;; `love . --record scenes/sundial.fnl --out f --frames 96 --fps 4` records the day.
(local {: sin : cos : pi : max} math)

(local day 24)                                ; seconds from sunrise to sunrise

(fn hour-angle [t]
  ;; Near 0 at sunrise, pi/2 at noon, near pi at sunset; the night is skipped, and
  ;; t = 0 (the still that --render draws) is mid-morning.
  (let [f (% (+ 0.3 (/ t day)) 1)] (+ 0.12 (* (- pi 0.24) f))))

(fn elevation [t] (sin (hour-angle t)))       ; 0 at the horizon, 1 overhead

(fn sun-direction [t]
  ;; Toward the sun: from the east (+x) over the south (-y) to the west (-x).
  (let [a (hour-angle t)]
    [(cos a) (* -0.45 (sin a)) (* 0.9 (sin a))]))

(fn sun-colour [t]
  (let [e (elevation t)]
    [1 (+ 0.55 (* 0.38 e)) (+ 0.3 (* 0.6 e))]))

(fn mix [a b f] (icollect [i x (ipairs a)] (+ x (* f (- (. b i) x)))))

{:name "sundial"
 :camera {:pos [7.6 -9.8 4.3] :yaw 128 :pitch 14 :fov 58}
 ;; The classic model's light (m in the player) follows the sun too.
 :light {:pos (fn [t] (icollect [_ x (ipairs (sun-direction t))] (* 30 x)))}
 ;; The modern look (see docs/scenes.md, Lighting); m in the player shows the classic model.
 :lighting {:lights [{:kind :sun :direction sun-direction :color sun-colour
                      :intensity (fn [t] (+ 1 (* 1.8 (elevation t)))) :softness 0.03}]
            :sky-zenith (fn [t] (mix [0.22 0.22 0.4] [0.25 0.45 0.85] (elevation t)))
            :sky-horizon (fn [t] (mix [0.95 0.6 0.4] [0.78 0.86 0.95] (elevation t)))
            :sun-size 2 :ambient 0.45 :ao 0.8 :ao-radius 0.5 :exposure 1.1}
 :render {:reflections 1 :draw-distance 300}
 :objects
 [{:kind :plane :height 0 :color [0.5 0.46 0.4] :roughness 0.9}
  ;; The dial: a round stone slab with a bronze ring, twelve hour marks and a gnomon.
  {:kind :rounded-cylinder :radius 2.6 :height 0.5 :rounding 0.08 :pos [0 0 0.25]
   :color [0.82 0.8 0.74] :roughness 0.7}
  {:kind :torus :radius 2.25 :thickness 0.05 :pos [0 0 0.5]
   :color [0.8 0.55 0.25] :mirror 0.8 :roughness 0.25}
  {:kind :polar :count 12 :pos [0 0 0.52] :color [0.25 0.22 0.2] :roughness 0.6
   :children [{:kind :box :size [0.45 0.08 0.06] :pos [1.85 0 0]}]}
  ;; The gnomon: a bronze wedge along y, its edge rising toward the north (+y).
  {:kind :intersection :pos [0 0.2 0.5] :color [0.8 0.55 0.25] :mirror 0.8 :roughness 0.25
   :children [{:kind :box :size [0.12 2.6 2.4] :pos [0 0 1.2]}
              {:kind :plane :normal [0 -0.6 0.8] :height 0.78}]}
  ;; Four pillars with balls on top, around the terrace.
  {:kind :polar :count 4 :color [0.85 0.83 0.78] :roughness 0.6
   :children [{:kind :union
               :children [{:kind :capped-cylinder :radius 0.22 :height 2.4 :pos [4.8 0 1.2]}
                          {:kind :sphere :radius 0.38 :pos [4.8 0 2.75]}]}]}]}

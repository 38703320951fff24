;; A Mandelbox, as on Shadertoy (issue 44): each turn folds the point into a box
;; (clamp), folds it through a sphere (a factor from the squared radius), scales it
;; and adds the point; the estimate is |z| / |dr|.
;;   SDL_VIDEODRIVER=offscreen love . --render examples/mandelbox.fnl --out box.png
(local {: abs : clamp : dot} math)

;; Tom Lowe's Mandelbox of scale `scale`, 10 turns: the box fold reflects each
;; component past +-1, the sphere fold scales by 4 inside radius 0.5 and inverts
;; between 0.5 and 1. dr carries the scale of the folds and turns.
(fn mandelbox [p scale]
  (var z p)
  (var dr 1)
  (for [i 1 10]
    (set z (- (* 2 (clamp z -1 1)) z))
    (let [r2 (dot z z)
          k (if (< r2 0.25) 4 (< r2 1) (/ 1 r2) 1)]
      (set z (+ (* z k scale) p))
      (set dr (+ (* dr k (abs scale)) 1))))
  (/ (length z) (abs dr)))

{:name "mandelbox"
 :camera {:pos [7 -8.6 5.6] :yaw 129 :pitch 28 :fov 50}
 :light {:pos [-10 -14 20]}
 :lighting {:lights [{:kind :sun :direction [-0.45 -0.55 0.7] :color [1 0.9 0.78]
                      :intensity 3 :softness 0.04}]
            :sky-zenith [0.22 0.35 0.65] :sky-horizon [0.8 0.8 0.85]
            :ambient 0.7 :ao 0.6 :ao-radius 0.2}
 :render {:reflections 0 :draw-distance 200}
 :objects
 [{:kind :plane :height -5 :color [0.5 0.52 0.55]}
  {:kind :custom :color [0.85 0.8 0.7] :roughness 0.5
   :params {:scale -2.5}
   :distance (fn [x y z scale] (mandelbox [x y z] scale))
   :bounds [4.7 4.7 4.7]}]}

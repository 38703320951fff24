;; A gyroid shell cut by a rounded box, as on Shadertoy (issue 44): the gyroid
;; sin(p) . cos(p.yzx) of the scaled point, its absolute value less a thickness, and
;; IQ's rounded box for the cut; a gold ball sits in the lattice.
;;   SDL_VIDEODRIVER=offscreen love . --render examples/gyroid-shell.fnl --out gyroid.png
(local {: abs : min : max : sin : cos : dot} math)

;; The gyroid's sheet at scale `scale`, `thickness` thick. The field changes by up to
;; sqrt(3) per unit of the scaled point and is divided by the scale, so its factor is
;; about 1.7: the loader measures it and divides by it.
(fn sd-gyroid [p scale thickness]
  (let [q (* p scale)]
    (- (abs (/ (dot (sin q) (cos [(. q 2) (. q 3) (. q 1)])) scale)) thickness)))

;; IQ's rounded box: half extents b, the edges rounded by r.
(fn sd-round-box [p b r]
  (let [q (+ (- (abs p) b) r)]
    (- (+ (length (max q 0)) (min (max (. q 1) (max (. q 2) (. q 3))) 0)) r)))

{:name "gyroid-shell"
 :camera {:pos [5 -6.6 4.6] :yaw 127 :pitch 23 :fov 50}
 :light {:pos [-10 -14 20]}
 :lighting {:lights [{:kind :sun :direction [-0.4 -0.55 0.75] :color [1 0.93 0.82]
                      :intensity 3 :softness 0.05}]
            :sky-zenith [0.3 0.45 0.75] :sky-horizon [0.82 0.86 0.92]
            :ambient 0.55 :ao 0.9 :ao-radius 0.3}
 :render {:reflections 1 :draw-distance 100}
 :objects
 [{:kind :plane :height 0 :color [0.6 0.6 0.58]}
  {:kind :custom :pos [0 0 1.1] :rotate [0 0 15] :color [0.25 0.55 0.65] :roughness 0.35
   :params {:scale 5 :thickness 0.04}
   :distance (fn [x y z scale thickness]
               (let [p [x y z]]
                 (max (sd-gyroid p scale thickness) (sd-round-box p [1.1 1.1 1.1] 0.15))))
   :bounds [1.1 1.1 1.1]}
  {:kind :sphere :radius 0.35 :pos [0 0 1.1] :color [1 0.75 0.3] :mirror 0.6 :roughness 0.2}]}

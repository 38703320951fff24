;; A chain of four links, as on Shadertoy (issue 44): IQ's link (a torus stretched
;; along y), every other one turned a quarter about y, placed in a loop.
;;   SDL_VIDEODRIVER=offscreen love . --render examples/chain-links.fnl --out chain.png
(local {: abs : min : max} math)

;; IQ's sdLink: a ring of radius r1 and tube r2 stretched by le along y.
(fn sd-link [p le r1 r2]
  (let [q [(. p 1) (max (- (abs (. p 2)) le) 0) (. p 3)]]
    (- (length [(- (length [(. q 1) (. q 2)]) r1) (. q 3)]) r2)))

{:name "chain-links"
 :camera {:pos [4 -6.6 3.2] :yaw 121 :pitch 19 :fov 48}
 :light {:pos [-10 -14 20]}
 :lighting {:lights [{:kind :sun :direction [-0.45 -0.55 0.7] :color [1 0.92 0.8]
                      :intensity 3 :softness 0.04}]
            :sky-zenith [0.25 0.4 0.75] :sky-horizon [0.85 0.85 0.9]
            :ambient 0.5 :ao 0.8 :ao-radius 0.3}
 :render {:reflections 2 :draw-distance 100}
 :objects
 [{:kind :plane :height 0 :color [0.35 0.37 0.4] :mirror 0.1}
  ;; The links' centres step `pitch` along y; odd ones lie in the x-y plane, even
  ;; ones turned a quarter (x and z swapped), so each passes through the next.
  {:kind :custom :pos [0 0 0.6] :rotate [0 0 -25] :color [0.85 0.85 0.9] :mirror 0.7 :roughness 0.15
   :params {:pitch 0.9}
   :distance (fn [x y z pitch]
               (var d math.huge)
               (for [i 1 4]
                 (let [q (- [x y z] [0 (* pitch (- i 2.5)) 0])
                       turned (if (= (% i 2) 0) [(. q 3) (. q 2) (. q 1)] q)]
                   (set d (min d (sd-link turned 0.25 0.32 0.1)))))
               d)
   :bounds [0.43 2.3 0.43]}]}

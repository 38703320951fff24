;; Domain repetition, as on Shadertoy (issue 44): one rounded pillar, repeated every
;; `spacing` units in x and y by mod of the point, and the whole cut to a 7 x 5 block by
;; a box; a cap and a plinth on each pillar, drawn as one shape.
;;   SDL_VIDEODRIVER=offscreen love . --render examples/pillar-grid.fnl --out pillars.png
(local {: abs : min : max : mod} math)

;; IQ's box, for the half extents b.
(fn sd-box [p b]
  (let [q (- (abs p) b)]
    (+ (length (max q 0)) (min (max (. q 1) (max (. q 2) (. q 3))) 0))))

;; A capped cylinder of radius r along z, from -h to h.
(fn sd-cylinder [p r h]
  (let [d (- (abs [(length [(. p 1) (. p 2)]) (. p 3)]) [r h])]
    (+ (min (max (. d 1) (. d 2)) 0) (length (max d 0)))))

;; One pillar in its cell's middle: a shaft with a square plinth and a square cap.
(fn sd-pillar [p]
  (min (sd-cylinder p 0.16 1)
       (sd-box (- p [0 0 -0.95]) [0.24 0.24 0.07])
       (sd-box (- p [0 0 0.95]) [0.22 0.22 0.06])))

{:name "pillar-grid"
 :camera {:pos [9.5 -10.5 5.5] :yaw 132 :pitch 18 :fov 50}
 :light {:pos [-10 -14 20]}
 :lighting {:lights [{:kind :sun :direction [-0.6 -0.35 0.55] :color [1 0.88 0.7]
                      :intensity 3 :softness 0.04}]
            :sky-zenith [0.25 0.4 0.75] :sky-horizon [0.9 0.82 0.72]
            :ambient 0.5 :ao 0.9 :ao-radius 0.4}
 :render {:reflections 0 :draw-distance 200}
 :objects
 [{:kind :plane :height 0 :color [0.55 0.5 0.45]}
  ;; The pillars in cells of `spacing`: the point's place in its cell from mod (a
  ;; pillar symmetric about the cell's middle, so the nearest pillar is its own
  ;; cell's), the block's box cutting the rows to 7 x 5.
  {:kind :custom :pos [0 0 1.02] :color [0.86 0.82 0.74] :roughness 0.7
   :params {:spacing 1.2}
   :distance (fn [x y z spacing]
               (let [p [x y z]
                     cell (- (mod (+ [x y] (* 0.5 spacing)) spacing) (* 0.5 spacing))]
                 (max (sd-pillar [(. cell 1) (. cell 2) z])
                      (sd-box p [4.2 3 1.02]))))
   :bounds [4.2 3 1.02]}
  {:kind :box :size [9 6.6 0.2] :pos [0 0 2.14] :color [0.8 0.76 0.7] :roughness 0.7}]}

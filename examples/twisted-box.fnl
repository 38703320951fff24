;; A twisted column and a bent bar, as on Shadertoy (issue 44): the point turned by
;; an angle that grows along an axis, through a helper that gives the turned vector,
;; then IQ's rounded box.
;;   SDL_VIDEODRIVER=offscreen love . --render examples/twisted-box.fnl --out twist.png
(local {: abs : min : max : sin : cos} math)

;; The vector [a b] turned by angle a (radians).
(fn rot [[u v] a]
  (let [c (cos a) s (sin a)]
    [(- (* c u) (* s v)) (+ (* s u) (* c v))]))

(fn sd-round-box [p b r]
  (let [q (+ (- (abs p) b) r)]
    (- (+ (length (max q 0)) (min (max (. q 1) (max (. q 2) (. q 3))) 0)) r)))

{:name "twisted-box"
 :camera {:pos [1.6 -9.5 3] :yaw 97 :pitch 12 :fov 50}
 :light {:pos [-10 -14 20]}
 :lighting {:lights [{:kind :sun :direction [-0.55 -0.5 0.65] :color [1 0.9 0.78]
                      :intensity 3 :softness 0.05}]
            :sky-zenith [0.28 0.42 0.75] :sky-horizon [0.85 0.86 0.9]
            :ambient 0.55 :ao 0.85 :ao-radius 0.35}
 :render {:reflections 1 :draw-distance 100}
 :objects
 [{:kind :plane :height 0 :color [0.6 0.58 0.55]}
  ;; A square column turned by `twist` radians per unit of height: its slope is
  ;; sqrt(1 + (twist r)^2) at distance r from the axis, which the loader measures.
  {:kind :custom :pos [-1.1 0 1.3] :color [0.3 0.55 0.85] :mirror 0.2 :roughness 0.2
   :params {:twist 1.4}
   :distance (fn [x y z twist]
               (let [[u v] (rot [x y] (* twist z))]
                 (sd-round-box [u v z] [0.4 0.4 1.3] 0.06)))
   :bounds [0.57 0.57 1.3]}
  ;; A bar bent about y: the point's x and z turned by an angle that grows with x.
  {:kind :custom :pos [1.3 0 0.45] :color [0.9 0.5 0.2] :roughness 0.4
   :params {:bend 0.5}
   :distance (fn [x y z bend]
               (let [[u w] (rot [x z] (* bend x))]
                 (sd-round-box [u y w] [1 0.25 0.25] 0.08)))
   :bounds [1.1 0.3 0.8]}]}

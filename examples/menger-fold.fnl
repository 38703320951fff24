;; A Menger sponge folded as IQ writes it, mod of the point in each of a few levels,
;; with the number of levels a parameter of at most 4 (issue 44).
;;   SDL_VIDEODRIVER=offscreen love . --render examples/menger-fold.fnl --out menger.png
(local {: abs : min : max} math)

(fn sd-box [p b]
  (let [q (- (abs p) b)]
    (+ (length (max q 0)) (min (max (. q 1) (max (. q 2) (. q 3))) 0))))

{:name "menger-fold"
 :camera {:pos [2.6 -3.4 2.4] :yaw 128 :pitch 28 :fov 50}
 :light {:pos [-10 -14 20]}
 :environment [0.78 0.86 0.95]
 :lighting {:sky-zenith [0.35 0.5 0.8] :sky-horizon [0.8 0.86 0.95] :ambient 0.55}
 :render {:reflections 0 :draw-distance 100}
 :objects
 [{:kind :plane :height -1.2 :color [0.55 0.55 0.5]}
  {:kind :custom :color [0.8 0.4 0.3]
   :params {:levels 3}
   :distance (fn [x y z levels]
               (let [p [x y z]]
                 (var d (sd-box p [1 1 1]))
                 (var s 1)
                 (for [m 1 (math.min levels 4)]
                   (let [a (- (math.mod (* p s) 2) 1)
                         s3 (* s 3)
                         r (abs (- 1 (* 3 (abs a))))
                         da (max (. r 1) (. r 2))
                         db (max (. r 2) (. r 3))
                         dc (max (. r 3) (. r 1))]
                     (set s s3)
                     (set d (max d (/ (- (min da db dc) 1) s)))))
                 d))
   :bounds [1 1 1]}]}

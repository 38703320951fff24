;; A smooth blend of several primitives with IQ's polynomial smooth minimum, as on
;; Shadertoy (issue 44): a ball, a torus, a box and a capsule, each joined to the
;; others over `k` units, written as helpers of vectors.
;;   SDL_VIDEODRIVER=offscreen love . --render examples/smooth-blend.fnl --out blend.png
(local {: abs : min : max : clamp : dot} math)

;; IQ's polynomial smooth minimum: min(a, b) less up to k / 4 where a and b are
;; within k of each other.
(fn smin [a b k]
  (let [h (max (- k (abs (- a b))) 0)]
    (- (min a b) (/ (* h h 0.25) k))))

(fn sd-sphere [p r] (- (length p) r))

;; A torus about z: radius R of the ring, r of the tube.
(fn sd-torus [p R r]
  (- (length [(- (length [(. p 1) (. p 2)]) R) (. p 3)]) r))

(fn sd-box [p b]
  (let [q (- (abs p) b)]
    (+ (length (max q 0)) (min (max (. q 1) (max (. q 2) (. q 3))) 0))))

;; A capsule from a to b of radius r.
(fn sd-capsule [p a b r]
  (let [pa (- p a) ba (- b a)
        h (clamp (/ (dot pa ba) (dot ba ba)) 0 1)]
    (- (length (- pa (* ba h))) r)))

{:name "smooth-blend"
 :camera {:pos [5.5 -7 3.6] :yaw 128 :pitch 17 :fov 50}
 :light {:pos [-10 -14 20]}
 :lighting {:lights [{:kind :sun :direction [-0.45 -0.6 0.65] :color [1 0.92 0.8]
                      :intensity 3 :softness 0.05}]
            :sky-zenith [0.3 0.45 0.8] :sky-horizon [0.85 0.85 0.9]
            :ambient 0.55 :ao 0.85 :ao-radius 0.35}
 :render {:reflections 1 :draw-distance 100}
 :objects
 [{:kind :plane :height 0 :color [0.58 0.6 0.62]}
  {:kind :custom :pos [0 0 0.9] :color [0.85 0.3 0.45] :mirror 0.15 :roughness 0.25
   :params {:k 0.35}
   :distance (fn [x y z k]
               (let [p [x y z]]
                 (-> (sd-sphere (- p [0 0 0.35]) 0.55)
                     (smin (sd-torus (- p [0 0 -0.3]) 0.9 0.2) k)
                     (smin (sd-box (- p [0.95 0.6 -0.45]) [0.3 0.3 0.3]) k)
                     (smin (sd-capsule p [-1.1 0.5 -0.5] [-0.6 -0.3 0.7] 0.17) k))))
   :bounds [1.45 1.25 0.95]}]}

;; Distance functions written with vectors, as on Shadertoy (issue 44): IQ's box, a
;; capsule from dot, clamp and mix, and a rounded cone, each point taken as one
;; vector (fn [p] ...) or as x y z with parameters after them.
;;   SDL_VIDEODRIVER=offscreen love . --render examples/vector-box.fnl --out box.png
(local {: abs : min : max : sqrt : clamp : mix : dot} math)

;; IQ's box, for the half extents b: a function of the file, a vector in and out.
(fn sd-box [p b]
  (let [q (- (abs p) b)]
    (+ (length (max q 0)) (min (max (. q 1) (max (. q 2) (. q 3))) 0))))

{:name "vector-box"
 :camera {:pos [0 -7 3] :yaw 90 :pitch 20 :fov 56}
 :light {:pos [-10 -14 20]}
 :environment [0.78 0.86 0.95]
 :lighting {:sky-zenith [0.35 0.5 0.8] :sky-horizon [0.8 0.86 0.95] :ambient 0.55}
 :render {:reflections 0 :draw-distance 100}
 :objects
 [{:kind :plane :height 0 :color [0.55 0.55 0.5]}

  {:kind :custom :pos [-1.8 0 0.6] :rotate [0 0 20] :color [0.3 0.5 0.9]
   :params {:w 0.7 :d 0.5 :h 0.6 :r 0.1}
   :distance (fn [x y z w d h r] (- (sd-box [x y z] (- [w d h] r)) r))
   :bounds [0.7 0.5 0.6]}

  {:kind :custom :pos [0 0 0.9] :color [0.9 0.55 0.2]
   :distance (fn [p]
               (let [a [-0.5 -0.3 -0.5] b [0.4 0.3 0.5] r 0.3
                     pa (- p a) ba (- b a)
                     h (clamp (/ (dot pa ba) (dot ba ba)) 0 1)]
                 (- (length (- p (mix a b h))) r)))
   :bounds [0.8 0.65 0.85]}

  ;; IQ's rounded cone: radius r1 at the bottom, r2 at height h above it.
  {:kind :custom :pos [1.8 0 0.45] :color [0.35 0.75 0.4]
   :distance (fn [[x y z]]
               (let [r1 0.45 r2 0.2 h 0.9
                     q [(length [x y]) z]
                     b (/ (- r1 r2) h)
                     a (sqrt (- 1 (* b b)))
                     k (dot q [(- b) a])]
                 (if (< k 0) (- (length q) r1)
                     (> k (* a h)) (- (length (- q [0 h])) r2)
                     (- (dot q [a b]) r1))))
   :bounds [0.45 0.45 1.15]}]}

;; Distance functions written in Fennel, the article's way, drawn on the GPU: each
;; :custom object's (fn [x y z ...] ...) is translated to GLSL when the scene loads
;; (see docs/scenes.md, Custom nodes). Its parameters after x y z come from :params, as
;; uniforms: editing a value there, or dragging the shell's slider (F2), compiles
;; nothing.
(local {: sqrt : abs : min : max : sin : cos} math)

(fn len3 [x y z] (sqrt (+ (* x x) (* y y) (* z z))))

{:name "custom"
 :camera {:pos [0 -10 4.4] :yaw 90 :pitch 21 :fov 56}
 :light {:pos [-10 -14 20]}
 :environment [0.78 0.86 0.95]
 :lighting {:sky-zenith [0.35 0.5 0.8] :sky-horizon [0.8 0.86 0.95]
            :ambient 0.55 :ao 0.8 :ao-radius 0.4}
 :render {:reflections 1 :draw-distance 200}
 :objects
 [{:kind :plane :height 0 :color [0.55 0.55 0.5]}

  ;; A gyroid shell cut by a sphere: the gyroid's field changes up to about
  ;; sqrt(3) * freq per unit, so the loader measures that and divides by it.
  {:kind :custom :pos [-2.6 0 1.3] :color [0.9 0.55 0.2] :mirror 0 :roughness 0.4
   :params {:freq 4 :thickness (param :shell 0.06 {:min 0.02 :max 0.2}) :radius 1.2}
   :distance (fn [x y z freq thickness radius]
               (let [fx (* freq x) fy (* freq y) fz (* freq z)
                     g (/ (+ (* (sin fx) (cos fy)) (* (sin fy) (cos fz)) (* (sin fz) (cos fx)))
                          freq)]
                 (max (- (abs g) thickness)
                      (- (sqrt (+ (* x x) (* y y) (* z z))) radius))))
   :bounds [1.2 1.2 1.2]}

  ;; A rounded box from helper functions, declared exact (the loader checks it).
  {:kind :custom :pos [0 1.2 0.9] :rotate [0 0 25] :color [0.3 0.5 0.9] :mirror 0.2
   :params {:w 0.9 :d 0.6 :h 0.6 :r 0.25}
   :lipschitz 1
   :distance (fn [x y z w d h r]
               (fn outside [a] (max a 0))
               (let [qx (- (abs x) (- w r)) qy (- (abs y) (- d r)) qz (- (abs z) (- h r))]
                 (- (+ (len3 (outside qx) (outside qy) (outside qz)) (min (max qx qy qz) 0))
                    r)))
   :bounds [0.9 0.6 0.6]}

  ;; A piecewise shape: a capsule written as three cases along z.
  {:kind :custom :pos [2.6 0 1.3] :color [0.35 0.75 0.4] :mirror 0
   :params {:half 0.8 :radius 0.5}
   :distance (fn [x y z half radius]
               (if (> z half) (- (len3 x y (- z half)) radius)
                   (< z (- half)) (- (len3 x y (+ z half)) radius)
                   (- (sqrt (+ (* x x) (* y y))) radius)))
   :bounds [0.5 0.5 1.3]}

  ;; Six spheres blended by a smooth minimum in a loop (var, set, for).
  {:kind :custom :pos [0 -1.6 0.45] :color [0.85 0.3 0.4] :mirror 0 :roughness 0.3
   :distance (fn [x y z]
               (var d 1000)
               (for [i 0 5]
                 (let [a (* i 1.0471976)
                       s (- (len3 (- x (* 0.7 (cos a))) (- y (* 0.7 (sin a))) z) 0.3)
                       k 0.25
                       h (max (- k (abs (- d s))) 0)]
                   (set d (- (min d s) (/ (* h h) (* 4 k))))))
               d)
   :bounds [1.1 1.1 0.45]}]}

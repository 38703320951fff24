;; A star prism: IQ's sdPolygon over a constant array of vertices, indexed by the
;; loop's counter, then extruded (issue 44).
;;   SDL_VIDEODRIVER=offscreen love . --render examples/polygon-prism.fnl --out star.png
(local {: abs : min : max : sqrt : clamp : dot} math)

;; Ten vertices of a five-pointed star, counter-clockwise.
(local star [[0 1] [-0.224 0.309] [-0.951 0.309] [-0.363 -0.118] [-0.588 -0.809]
             [0 -0.382] [0.588 -0.809] [0.363 -0.118] [0.951 0.309] [0.224 0.309]])

;; The signed distance to the polygon `star` in the plane (IQ's sdPolygon): the
;; nearest edge, and the sign from the crossings of a ray along x.
(fn sd-polygon [p]
  (var d (dot (- p (. star 1)) (- p (. star 1))))
  (var s 1)
  (for [i 1 10]
    (let [j (if (= i 1) 10 (- i 1))
          vi (. star i)
          vj (. star j)
          e (- vj vi)
          w (- p vi)
          b (- w (* e (clamp (/ (dot w e) (dot e e)) 0 1)))
          above (>= (. p 2) (. vi 2))
          below (< (. p 2) (. vj 2))
          right (> (* (. e 1) (. w 2)) (* (. e 2) (. w 1)))]
      (set d (min d (dot b b)))
      (when (or (and above below right) (and (not above) (not below) (not right)))
        (set s (- s)))))
  (* s (sqrt d)))

{:name "polygon-prism"
 :camera {:pos [0 -6 3.5] :yaw 90 :pitch 30 :fov 50}
 :light {:pos [-10 -14 20]}
 :environment [0.78 0.86 0.95]
 :lighting {:sky-zenith [0.35 0.5 0.8] :sky-horizon [0.8 0.86 0.95] :ambient 0.55}
 :render {:reflections 0 :draw-distance 100}
 :objects
 [{:kind :plane :height 0 :color [0.55 0.55 0.5]}
  {:kind :custom :pos [0 0 0.3] :rotate [0 0 10] :color [0.9 0.7 0.2]
   :params {:height 0.3}
   :distance (fn [x y z height]
               (let [w [(sd-polygon [x y]) (- (abs z) height)]]
                 (+ (min (max (. w 1) (. w 2)) 0) (length (max w 0)))))
   :bounds [1 1 0.3]}]}

;; The article's CPU program, for `make bench` to measure in the same run as everything
;; else (its pixel rate is the unit of the "1,000x the article" goal). Written again
;; from the article's description, in its style, because its speed is the point: a
;; vector is a fresh three-element table and every operation on one a function; an
;; object is a table with an :sdf function called as a method; the distance estimator
;; returns the distance and the colour as two values; a ray marches with a fixed
;; epsilon of 1e-4 and up to 500 steps; a normal is three one-sided differences of the
;; whole scene; a point is lit by Lambert with a shadow ray (half as bright when it
;; hits) and mirrored three times with the article's colour blend; each pixel is one
;; love.graphics.points call with its colour set. The scene, camera and light are the
;; seed's (scenes/seed.fnl, the article's final scene).

(local sqrt math.sqrt)
(local abs math.abs)
(local max math.max)

(local march-delta 0.0001)
(local max-steps 500)
(local draw-distance 1000)
(local reflection-count 3)

(fn vec3 [x y z]
  (if (= x nil) [0 0 0]
      (and (= y nil) (= z nil)) [x x x]
      [x y (or z 0)]))

(fn vec-add [[ax ay az] [bx by bz]] [(+ ax bx) (+ ay by) (+ az bz)])
(fn vec-sub [[ax ay az] [bx by bz]] [(- ax bx) (- ay by) (- az bz)])
(fn vec-mul [[ax ay az] [bx by bz]] [(* ax bx) (* ay by) (* az bz)])
(fn dot [[ax ay az] [bx by bz]] (+ (* ax bx) (* ay by) (* az bz)))
(fn cross [[ax ay az] [bx by bz]]
  [(- (* ay bz) (* az by)) (- (* az bx) (* ax bz)) (- (* ax by) (* ay bx))])
(fn vec-length [[x y z]] (sqrt (+ (^ x 2) (^ y 2) (^ z 2))))
(fn norm [v]
  (let [l (vec-length v)
        [x y z] v]
    [(/ x l) (/ y l) (/ z l)]))

(fn sphere-sdf [{:pos [cx cy cz] : radius} [x y z]]
  (- (sqrt (+ (^ (- cx x) 2) (^ (- cy y) 2) (^ (- cz z) 2))) radius))

(fn box-sdf [{:pos [cx cy cz] :sides [sx sy sz]} [x y z]]
  (sqrt (+ (^ (max 0 (- (abs (- cx x)) (/ sx 2))) 2)
           (^ (max 0 (- (abs (- cy y)) (/ sy 2))) 2)
           (^ (max 0 (- (abs (- cz z)) (/ sz 2))) 2))))

(fn plane-sdf [plane [_ _ z]] (- z plane.height))

(local scene
  [{:sdf box-sdf :sides [5 5 5] :pos [-2.7 -2 2.5] :color [0.79 0.69 0.59]}
   {:sdf box-sdf :sides [5 5 5] :pos [2.7 2 2.5] :color [0.75 0.08 0.66]}
   {:sdf box-sdf :sides [5 5 5] :pos [0 0 7.5] :color [0.33 0.73 0.42]}
   {:sdf sphere-sdf :radius 2.5 :pos [-2.7 2.5 2.5] :color [0.56 0.11 0.05]}
   {:sdf sphere-sdf :radius 10 :pos [6 -20 10] :color [0.97 0.71 0.17]}
   {:sdf plane-sdf :height 0 :color [0.97 0.27 0.35]}])

(local light [-30 20 20])
(local sky [0.901 0.976 1])

(fn estimate [point]
  (var nearest draw-distance)
  (var color [0 0 0])
  (each [_ object (ipairs scene)]
    (let [d (object:sdf point)]
      (when (< d nearest)
        (set nearest d)
        (set color object.color))))
  (values nearest color))

(fn move-point [point dir distance]
  (vec-add point (vec-mul dir (vec3 distance))))

(fn march [origin dir]
  (var steps 0)
  (var travelled 0)
  (var color nil)
  (var going? true)
  (while going?
    (let [(d c) (estimate (move-point origin dir travelled))]
      (when (or (< d march-delta) (>= travelled draw-distance) (> steps max-steps))
        (set going? false))
      (set travelled (+ travelled d))
      (set color c)
      (set steps (+ steps 1))))
  (values travelled color steps))

(fn normal-at [[px py pz]]
  (let [(d) (estimate [px py pz])
        (dx) (estimate [(- px march-delta) py pz])
        (dy) (estimate [px (- py march-delta) pz])
        (dz) (estimate [px py (- pz march-delta)])]
    (norm [(- d dx) (- d dy) (- d dz)])))

(fn clamp [v lo hi] (if (< v lo) lo (> v hi) hi v))

(fn above [point normal]
  (vec-add point (vec-mul normal (vec3 (* march-delta 2)))))

(fn lightness [point]
  (let [normal (normal-at point)
        to-light (norm (vec-sub light point))
        (d) (march (above point normal) to-light)
        l (clamp (dot to-light normal) 0 1)]
    (if (< d draw-distance) (* l 0.5) l)))

(fn reflected [color point dir]
  (var [c p d n] [color point dir (normal-at point)])
  (var i 0)
  (var going? true)
  (while (and going? (< i reflection-count))
    (let [r (vec-sub d (vec-mul (vec-mul (vec3 (dot d n)) n) [2 2 2]))
          (dist hit-color) (march (above p n) r)]
      (if (< dist draw-distance)
          (let [q (move-point p r dist)
                l (/ (lightness q) 2)
                [r0 g0 b0] c
                [r1 g1 b1] hit-color]
            (set p q)
            (set n (normal-at q))
            (set d r)
            (set c [(* (+ r0 (* r1 l)) 0.66) (* (+ g0 (* g1 l)) 0.66) (* (+ b0 (* b1 l)) 0.66)]))
          (set going? false)))
    (set i (+ i 1)))
  c)

(fn shade [point color dir]
  (-> color
      (vec-mul (vec3 (lightness point)))
      (reflected point dir)))

(fn draw! [width height]
  "Draw the seed scene the article's way into the current target: one point per pixel."
  ;; The seed's camera: at [20 50 20], yaw 255, pitch 15 (a look-at point one unit
  ;; ahead), field of view 60 degrees.
  (let [ro [20 50 20]
        yaw (math.rad 255)
        pitch (math.rad 15)
        lookat (vec-add ro [(* (math.cos pitch) (math.cos yaw)) (* (math.cos pitch) (math.sin yaw))
                            (- (math.sin pitch))])
        projection (/ 1 (math.tan (math.rad 30)))
        f (norm (vec-sub lookat ro))
        c (vec-add ro (vec-mul f (vec3 projection)))
        r (norm (cross [0 0 -1] f))
        u (cross f r)]
    (for [y 0 (- height 1)]
      (for [x 0 (- width 1)]
        (let [uv-x (* (- (/ x width) 0.5) (/ width height))
              uv-y (- (/ y height) 0.5)
              i (vec-add c (vec-add (vec-mul r (vec3 uv-x)) (vec-mul u (vec3 uv-y))))
              rd (norm (vec-sub i ro))
              (dist color) (march ro rd)]
          (if (< dist draw-distance)
              (love.graphics.setColor (shade (move-point ro rd dist) color rd))
              (love.graphics.setColor sky))
          (love.graphics.points (+ x 0.5) (+ y 0.5)))))))

{: draw! : estimate : march}

;; A city of ten thousand objects to fly through (issue 12): 100 x 100 blocks of
;; towers, each a box of its own height and colour, and a dome on one block in seven.
;; So many spheres and boxes form a field: float textures and a grid, so a ray tests
;; only the towers along its way (see docs/how-it-works.md, Many objects). Scene files have no
;; random numbers: the city comes from its own hash.
(fn hash [i k]
  ;; A repeatable number in [0, 1) for block i and salt k.
  (let [x (math.sin (+ (* i 12.9898) (* k 78.233)))]
    (- (* x 43758.5453) (math.floor (* x 43758.5453)))))

(local blocks 100)       ; along each side
(local pitch 4)          ; block to block
(local objects [{:kind :plane :height 0 :color [0.32 0.32 0.34]}])
(for [bx 0 (- blocks 1)]
  (for [by 0 (- blocks 1)]
    (let [i (+ (* bx blocks) by)
          x (* pitch (- bx (/ blocks 2)))
          y (* pitch (- by (/ blocks 2)))
          ;; Taller towards the centre, with a few skyscrapers.
          centre (/ (math.sqrt (+ (* x x) (* y y))) (* pitch blocks 0.5))
          tall (if (< (hash i 3) 0.04) 3 1)
          height (* tall (+ 1.5 (* 9 (hash i 1) (math.max 0.15 (- 1 centre)))))
          width (+ 2 (* 1.2 (hash i 2)))
          ;; Pale stone, warm brick or blue glass.
          kind (hash i 4)
          shade (+ 0.7 (* 0.3 (hash i 5)))
          color (if (< kind 0.45) [(* shade 0.82) (* shade 0.78) (* shade 0.7)]
                    (< kind 0.75) [(* shade 0.7) (* shade 0.42) (* shade 0.3)]
                    [(* shade 0.3) (* shade 0.42) (* shade 0.55)])]
      (if (< (hash i 7) (/ 1 7))
          (table.insert objects {:kind :sphere :pos [x y 0] :radius (* 0.5 (+ width 0.4))
                                 :color [0.75 0.62 0.38]})
          (table.insert objects {:kind :box :pos [x y (* 0.5 height)] :size [width width height]
                                 : color})))))

{:name "city"
 ;; Down an avenue from the city's edge.
 :camera {:pos [2 -215 22] :yaw 90 :pitch 6 :fov 60}
 :light {:pos [-300 -400 600]}
 :environment [0.6 0.68 0.8]
 :lighting {:lights [{:kind :sun :direction [-0.5 -0.6 0.62] :color [1 0.88 0.72]
                      :intensity 3 :softness 0}]
            :sky-zenith [0.3 0.45 0.8] :sky-horizon [0.85 0.82 0.78]
            :ambient 0.35 :ao 0.6 :ao-radius 0.6 :fog 0.0015 :fog-color [0.85 0.82 0.78]
            :exposure 1}
 :render {:reflections 1 :draw-distance 600}
 :objects objects}

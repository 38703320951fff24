;; A ring of mirrored spheres around a stepped tower, with step-count glow on the
;; sky: reflections of reflections, shadows across the floor, all three kinds.
(local ring
  (fcollect [i 1 8]
    (let [a (* (- i 1) (/ math.pi 4))
          hue (/ (- i 1) 8)]
      {:kind :sphere :radius 1.1
       :pos [(* 7 (math.cos a)) (* 7 (math.sin a)) 1.1]
       :color [(+ 0.5 (* 0.5 (math.cos (* 2 math.pi hue))))
               (+ 0.5 (* 0.5 (math.cos (* 2 math.pi (- hue 0.33)))))
               (+ 0.5 (* 0.5 (math.cos (* 2 math.pi (- hue 0.67)))))]})))

(local tower
  [{:kind :box :size [4 4 1] :pos [0 0 0.5] :color [0.85 0.85 0.8]}
   {:kind :box :size [3 3 1] :pos [0 0 1.5] :color [0.75 0.75 0.7]}
   {:kind :box :size [2 2 1] :pos [0 0 2.5] :color [0.65 0.65 0.6]}
   {:kind :sphere :radius 1 :pos [0 0 4] :color [0.95 0.95 0.95]}
   {:kind :plane :height 0 :color [0.35 0.4 0.5]}])

(each [_ o (ipairs tower)] (table.insert ring o))

{:name "gallery"
 :camera {:pos [15 -9 7] :yaw 149 :pitch 20 :fov 60}
 :light {:pos [-12 -18 25]}
 :environment [0.05 0.07 0.12]
 :render {:reflections 4 :shadows true :glow true :draw-distance 300}
 :objects ring}

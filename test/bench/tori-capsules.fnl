;; A benchmark scene for the primitives whose GLSL the translator writes (torus and
;; capsule, src/sdf/primitives/*.fnl :fennel): 48 of them as tree objects over a floor,
;; so that their distance functions are most of a frame's work.
{:name "tori-capsules"
 :camera {:pos [0 -16 9] :yaw 90 :pitch 28 :fov 60}
 :light {:pos [-10 -20 30]}
 :render {:reflections 1}
 :objects (let [out [{:kind :plane :height 0 :color [0.6 0.6 0.6]}]]
            (for [i 0 5]
              (for [j 0 3]
                (let [x (* 3 (- i 2.5)) y (* 3 (- j 1.5))]
                  (table.insert out {:kind :torus :radius 0.8 :thickness 0.25 :pos [x y 0.8]
                                     :rotate [(* 15 i) (* 10 j) 0] :color [0.8 0.4 0.3]})
                  (table.insert out {:kind :capsule :a [-0.6 0 0] :b [0.6 0 0.4] :radius 0.3
                                     :pos [(+ x 1.2) (+ y 1.2) 0.5] :color [0.3 0.5 0.8]}))))
            out)}

;; A shelf of solids: the five platonic solids (tetrahedron, cube, octahedron,
;; dodecahedron, icosahedron) on the top board, and below them a pyramid, a
;; triangular prism, a rhombus tile, a death star, a cut hollow sphere, the cheap
;; octahedron bound, a xor of two boxes, a cylinder clipped by an intersection and a
;; solid turned about a tilted axis. Every solid sits on a rounded shelf board.
(fn on-shelf [x z node]
  (doto node (tset :pos [x 0 z])))

(local board {:kind :round-box :size [11 1.8 0.2] :radius 0.05})

{:name "platonic shelf"
 :camera {:pos [0.3 -10 3.4] :yaw 90 :pitch 6 :fov 64}
 :light {:pos [-6 -14 16]}
 :environment [0.85 0.82 0.78]
 ;; The modern look (see docs/scenes.md, Lighting); m in the player shows the classic model.
 :lighting {:lights [{:kind :sun :direction [-0.35 -0.75 0.55] :intensity 3 :softness 0.05}]
            :sky-zenith [0.4 0.5 0.7] :sky-horizon [0.85 0.82 0.78]
            :ambient 0.5 :ao 0.9 :ao-radius 0.4 :exposure 1.1}
 :render {:reflections 1 :draw-distance 200}
 :objects
 [{:kind :plane :height 0 :color [0.5 0.42 0.35]}
  {:kind :plane :normal [0 -1 0] :height -1.2 :color [0.8 0.78 0.72]}
  {:kind :union :color [0.55 0.35 0.2] :mirror 0
   :children [(on-shelf 0 1.2 (doto (collect [k v (pairs board)] k v)))
              (on-shelf 0 3.5 (doto (collect [k v (pairs board)] k v)))]}
  ;; Top board: the platonic solids.
  {:kind :union :color [0.85 0.3 0.3] :mirror 0.3
   :children [(on-shelf -4.2 4.05 {:kind :tetrahedron :size 0.6})
              (on-shelf -2.1 4.05 {:kind :box :size [0.85 0.85 0.85] :color [0.9 0.6 0.2]})
              (on-shelf 0 4.25 {:kind :octahedron :size 0.65 :color [0.9 0.85 0.25]})
              (on-shelf 2.1 4.2 {:kind :dodecahedron :size 0.55 :color [0.3 0.7 0.4]})
              (on-shelf 4.2 4.2 {:kind :icosahedron :size 0.55 :color [0.3 0.5 0.9]})]}
  ;; Lower board.
  {:kind :union :color [0.75 0.75 0.8] :mirror 0.2
   :children [(on-shelf -4.5 1.3 {:kind :pyramid :base 0.9 :height 0.9 :color [0.85 0.75 0.45]})
              (on-shelf -3.3 1.7 {:kind :tri-prism :radius 0.25 :height 0.8 :rotate [90 0 0]
                                   :color [0.5 0.8 0.8]})
              (on-shelf -2.1 1.45 {:kind :rhombus :length-a 0.5 :length-b 0.3 :height 0.15 :radius 0.03
                                    :rotate [90 0 0] :color [0.9 0.4 0.6]})
              (on-shelf -0.9 1.75 {:kind :death-star :radius 0.45 :cutter-radius 0.35 :offset 0.5
                                    :rotate [0 -60 0] :color [0.6 0.6 0.65]})
              (on-shelf 0.3 1.75 {:kind :cut-hollow-sphere :radius 0.45 :cut 0.2 :thickness 0.04
                                   :rotate [70 0 0] :color [0.95 0.95 0.9]})
              (on-shelf 1.5 1.75 {:kind :cheap-octahedron :size 0.45 :color [0.9 0.85 0.25]})
              (on-shelf 2.7 1.65 {:kind :xor :color [0.4 0.5 0.9]
                                  :children [{:kind :box :size [0.7 0.7 0.7]}
                                             {:kind :box :size [0.5 0.5 0.5] :pos [0.25 -0.25 0.25]}]})
              (on-shelf 3.9 1.65 {:kind :intersection :color [0.7 0.9 0.5]
                                  :children [{:kind :cylinder :radius 0.3}
                                             {:kind :sphere :radius 0.4}]})
              (on-shelf 4.9 1.65 {:kind :rotate :axis [1 1 0] :angle 35 :color [0.9 0.5 0.3]
                                  :children [{:kind :scale :factor 0.4
                                              :children [{:kind :capped-cylinder :radius 0.6 :height 1.2}]}]})]}]}

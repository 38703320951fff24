;; The article's final scene ("Raymarching with Fennel and LÖVE"), exactly: three boxes,
;; two spheres and a ground plane, seen from high above with three mirror bounces.
{:name "seed"
 :camera {:pos [20 50 20] :yaw 255 :pitch 15 :fov 60}
 :light {:pos [-30 20 20]}
 :environment [0.901 0.976 1]
 ;; The article's march: 500 steps, a fixed hit epsilon, one-sided normals of the
 ;; whole scene's distance, no over-relaxation, every object marched everywhere (no
 ;; bounds), and a ray out of steps shaded where it stopped. The defaults are faster and more accurate: see
 ;; report/report.md and `make bench`.
 :render {:max-steps 500 :epsilon 1e-4 :draw-distance 1000
          :reflections 3 :shadows true :glow false
          :hit-test :fixed :normals :one-sided :normals-of :scene :relaxation 1 :bounds false
          :out-of-steps :surface}
 :objects [{:kind :box :size [5 5 5] :pos [-2.7 -2 2.5] :color [0.79 0.69 0.59]}
           {:kind :box :size [5 5 5] :pos [2.7 2 2.5] :color [0.75 0.08 0.66]}
           {:kind :box :size [5 5 5] :pos [0 0 7.5] :color [0.33 0.73 0.42]}
           {:kind :sphere :radius 2.5 :pos [-2.7 2.5 2.5] :color [0.56 0.11 0.05]}
           {:kind :sphere :radius 10 :pos [6 -20 10] :color [0.97 0.71 0.17]}
           {:kind :plane :height 0 :color [0.97 0.27 0.35]}]}

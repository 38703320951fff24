;; Stress: epsilon 0 with the fixed hit test: a step counts as a hit only when the
;; distance is negative, which sphere tracing toward an exact distance hardly ever
;; produces, so rays that reach a surface converge on it until the step budget runs
;; out (a hit, since the distance stays below the draw distance). The hit points are
;; as exact as float32 gets; the normal step (never below 1e-6 of the distance) and
;; the ray offsets must keep secondary rays from starting inside the surface.
;; (:out-of-steps :surface keeps the article's shading of rays out of steps, which this
;; scene is about; the default would show them the background.)
{:name "stress epsilon zero fixed"
 :camera {:pos [0 -8 3] :yaw 90 :pitch 15 :fov 60}
 :light {:pos [-30 -20 20]}
 :render {:epsilon 0 :hit-test :fixed :out-of-steps :surface}
 :objects [{:kind :sphere :radius 1 :pos [1 0 1] :color [0.56 0.11 0.05]}
           {:kind :box :size [1.5 1.5 1.5] :pos [-1.5 1 0.75] :color [0.79 0.69 0.59]}
           {:kind :plane :height 0 :color [0.97 0.27 0.35]}]}

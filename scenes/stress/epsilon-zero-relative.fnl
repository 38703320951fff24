;; Stress: epsilon 0 with the relative hit test (0 times the distance travelled): as
;; epsilon-zero-fixed.fnl, every ray that reaches a surface spends the whole step
;; budget converging on it, with over-relaxation (the default's 1.5) stepping past the
;; surface and falling back.
;; (:out-of-steps :surface keeps the article's shading of rays out of steps, which this
;; scene is about; the default would show them the background.)
{:name "stress epsilon zero relative"
 :camera {:pos [0 -8 3] :yaw 90 :pitch 15 :fov 60}
 :light {:pos [-30 -20 20]}
 :render {:epsilon 0 :hit-test :relative :out-of-steps :surface}
 :objects [{:kind :sphere :radius 1 :pos [1 0 1] :color [0.56 0.11 0.05]}
           {:kind :box :size [1.5 1.5 1.5] :pos [-1.5 1 0.75] :color [0.79 0.69 0.59]}
           {:kind :plane :height 0 :color [0.97 0.27 0.35]}]}

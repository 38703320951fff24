;; Stress: a box 1e-4 thick (a 4 x 4 sheet standing on the ground) seen obliquely, a
;; sphere behind it. The hit test and the normal step must stay well under the sheet's
;; thickness: a normal step wider than 1e-4 reaches through the sheet, the differences
;; see both faces and the normal comes out wrong or zero; a ray offset (twice the
;; normal step) wider than the sheet starts shadow and mirror rays on its far side.
{:name "stress thin box"
 :camera {:pos [6 -6 3] :yaw 125 :pitch 15 :fov 60}
 :light {:pos [-30 -20 20]}
 :objects [{:kind :box :size [4 0.0001 4] :pos [0 0 2] :color [0.79 0.69 0.59]}
           {:kind :sphere :radius 1 :pos [0 3 1] :color [0.56 0.11 0.05]}
           {:kind :plane :height 0 :color [0.97 0.27 0.35]}]}

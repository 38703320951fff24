;; A torus alone, as tools/mesh-vs-fogleman/shapes.py's torus_shape (issue 46's
;; third case): ring radius 1, tube radius 0.35, around z.
{:name "torus"
 :camera {:pos [0 -4 2] :yaw 0 :pitch 25}
 :objects [{:kind :torus :radius 1 :thickness 0.35}]}

;; Spheres only: no box and no plane code ends up in this scene's shader.
{:name "spheres"
 :camera {:pos [0 -14 4] :yaw 90 :pitch 12 :fov 60}
 :light {:pos [-20 -30 40]}
 :environment [0.2 0.25 0.35]
 :render {:reflections 2 :shadows true}
 :objects [{:kind :sphere :radius 2 :pos [0 0 0] :color [0.9 0.9 0.95]}
           {:kind :sphere :radius 1 :pos [3.2 -1 -0.8] :color [0.85 0.25 0.2]}
           {:kind :sphere :radius 1 :pos [-3.2 -1 -0.8] :color [0.2 0.45 0.85]}
           {:kind :sphere :radius 0.6 :pos [1.4 -3 -1.2] :color [0.95 0.8 0.2]}
           {:kind :sphere :radius 0.6 :pos [-1.4 -3 -1.2] :color [0.3 0.8 0.35]}
           {:kind :sphere :radius 40 :pos [0 0 -42] :color [0.55 0.55 0.6]}]}

;; Hand-written analytic distances, independent of the descriptors and the tape: the
;; oracles the specs compare the generated CPU evaluator against.

(local {: sqrt : abs : max : min} math)

(fn sphere [x y z [cx cy cz] r]
  "Distance from (x y z) to the sphere of radius r around c."
  (let [dx (- x cx) dy (- y cy) dz (- z cz)]
    (- (sqrt (+ (* dx dx) (* dy dy) (* dz dz))) r)))

(fn box [x y z [cx cy cz] [hx hy hz]]
  "Signed distance from (x y z) to the axis-aligned box centred on c, half extents h."
  (let [qx (- (abs (- x cx)) hx) qy (- (abs (- y cy)) hy) qz (- (abs (- z cz)) hz)
        ox (max qx 0) oy (max qy 0) oz (max qz 0)]
    (+ (sqrt (+ (* ox ox) (* oy oy) (* oz oz))) (min (max qx qy qz) 0))))

(fn plane [_ _ z h]
  "Signed distance to the plane z = h, solid below."
  (- z h))

{: sphere : box : plane}

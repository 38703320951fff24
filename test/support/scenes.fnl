;; Scene files the specs write or load, shared where two specs draw the same scene.

(fn marched-mix [n ?render]
  "The text of a scene of `n` spheres, rotated tori and capsules (a third each)
scattered over a 40 x 40 x 10 region above a floor: the tori and capsules are
placed, turned and coloured alone, so a field holds them as marched members.
`?render` is its :render table's text (shadows, one bounce, no relaxation)."
  (.. "(var seed 5)
(fn rnd [] (set seed (% (+ (* seed 1103515245) 12345) 2147483648)) (/ seed 2147483648))
(local objects [{:kind :plane :height 0 :color [0.6 0.6 0.6]}])
(for [i 1 " n "]
  (let [x (+ -20 (* 40 (rnd))) y (+ -20 (* 40 (rnd))) z (+ 0.8 (* 10 (rnd)))
        r (+ 0.3 (* 0.5 (rnd)))
        color [(rnd) (rnd) (rnd)]
        k (% i 3)]
    (table.insert objects (if (= k 0) {:kind :sphere :pos [x y z] :radius r : color}
                              (= k 1) {:kind :torus :radius r :thickness (* 0.3 r) :pos [x y z]
                                       :rotate [(* 90 (rnd)) (* 90 (rnd)) 0] : color}
                              {:kind :capsule :a [(- r) 0 0] :b [r 0 (* 0.5 r)] :radius (* 0.4 r)
                               :pos [x y z] : color}))))
{:camera {:pos [0 -35 12] :yaw 90 :pitch 15 :fov 60}
 :light {:pos [-20 -30 40]}
 :render " (or ?render "{:shadows true :reflections 1 :relaxation 1}") "
 :objects objects}"))

{: marched-mix}

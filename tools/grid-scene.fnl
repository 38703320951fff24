;; The scaling scenes of issue 29's grids and blends, written as scene files:
;;   luajit tools/fnl.lua tools/grid-scene.fnl mixed|blend N OUT.fnl
;; mixed: N boxes, rotated tori and capsules (a third each) over a 40 x 40 x 10
;; region above a floor, their size shrinking as 1 / sqrt(N) so that together they
;; cover about the same share of the picture (as make bench's scaling row); hard
;; shadows, one mirror bounce. blend: a smooth union of N spheres in an 8 x 8 x 3
;; region, radii and blend radius shrinking as 1 / sqrt(N), a quarter mirror.
(local [kind n out] arg)
(local n (assert (tonumber n) "N: a whole number"))
(local head
  "(var seed 12345)
(fn rnd [] (set seed (% (+ (* seed 1103515245) 12345) 2147483648)) (/ seed 2147483648))
")
(local text
  (case kind
    :mixed (.. head "(local s (* 1.2 (math.sqrt (/ 10 " n "))))
(local objects [{:kind :plane :height 0 :color [0.6 0.6 0.6]}])
(for [i 1 " n "]
  (let [x (+ -20 (* 40 (rnd))) y (+ -20 (* 40 (rnd))) z (+ 0.5 (* 10 (rnd)))
        color [(+ 0.3 (* 0.7 (rnd))) (+ 0.3 (* 0.7 (rnd))) (+ 0.3 (* 0.7 (rnd)))]
        k (% i 3)]
    (table.insert objects
                  (if (= k 0) {:kind :box :size [(* 1.4 s) (* 1.4 s) (* 1.4 s)] :pos [x y z] : color}
                      (= k 1) {:kind :torus :radius (* 0.8 s) :thickness (* 0.3 s) :pos [x y z]
                               :rotate [(* 90 (rnd)) (* 90 (rnd)) 0] : color}
                      {:kind :capsule :a [(* -0.6 s) 0 0] :b [(* 0.6 s) 0 (* 0.3 s)] :radius (* 0.35 s)
                       :pos [x y z] : color}))))
{:name \"mixed " n "\"
 :camera {:pos [0 -35 12] :yaw 90 :pitch 15 :fov 60}
 :light {:pos [-20 -30 40]}
 :render {:shadows true :reflections 1}
 :objects objects}
")
    :blend (.. head "(local s (math.sqrt (/ 200 " n ")))
{:name \"blend " n "\"
 :camera {:pos [0 -14 6] :yaw 90 :pitch 18 :fov 60}
 :light {:pos [-20 -30 40]}
 :render {:shadows true :reflections 1}
 :objects [{:kind :plane :height 0 :color [0.6 0.6 0.6]}
           {:kind :smooth-union :radius (* 0.3 s) :pos [0 0 2] :color [0.8 0.5 0.3] :mirror 0.25
            :children (fcollect [i 1 " n "]
                        {:kind :sphere :radius (* s (+ 0.15 (* 0.25 (rnd))))
                         :pos [(- (* 8 (rnd)) 4) (- (* 8 (rnd)) 4) (- (* 3 (rnd)) 1.5)]})}]}
")
    _ (error "kind: mixed or blend")))
(with-open [f (assert (io.open out :w))] (f:write text))

;; A test scene for tools/check-states.sh (SCENES=test/states/grid), after
;; test/states/hue-colours.fnl (the :hue machinery) as test/states/hue.fnl is, over
;; issue 29's blends: a smooth union of 300 spheres and a union of 60 rotated tori,
;; each one loop over its children with a grid.
(var seed 5)
(fn rnd [] (set seed (% (+ (* seed 1103515245) 12345) 2147483648)) (/ seed 2147483648))

(local spheres (fcollect [_ 1 300]
                 {:kind :sphere :radius (+ 0.15 (* 0.2 (rnd)))
                  :pos [(- (* 5 (rnd)) 2.5) (- (* 5 (rnd)) 2.5) (- (* 3 (rnd)) 1.5)]}))
(local tori (fcollect [_ 1 60]
              {:kind :torus :radius 0.5 :thickness 0.15
               :pos [(- (* 16 (rnd)) 8) (- (* 16 (rnd)) 8) 0.6] :rotate [(* 90 (rnd)) 0 (* 90 (rnd))]}))

{:name "states: hue over grids"
 :camera camera :light light :environment sky
 :render {:reflections 0 :draw-distance 200}
 :objects
 [{:kind :plane :height 0 :color c :mirror 0}
  {:kind :smooth-union :radius 0.25 :color c :mirror 0 :pos [0 0 2] :children spheres}
  {:kind :union :color c :mirror 0 :children tori}]}

;; expect: test/corpus/custom-lipschitz-too-small.fnl:4: objects[1].lipschitz: declares 1, but the distance changes by 6.87 per unit at [-0.377 0.376 -0.411] (sampled outside the shape, over its bounds); declare at least 6.87, leave :lipschitz out to have it measured, or add :trust-lipschitz true to use 1 anyway (a ray may then step past the surface)
;; A gyroid shell cut by a ball, declared 1-Lipschitz: its field changes faster;
;; refused, not torn.
{:objects [{:kind :custom :bounds [1 1 1] :lipschitz 1
            :distance (fn [x y z]
                        (math.max (- (math.abs (+ (* (math.sin (* 4 x)) (math.cos (* 4 y)))
                                                  (* (math.sin (* 4 y)) (math.cos (* 4 z)))
                                                  (* (math.sin (* 4 z)) (math.cos (* 4 x)))))
                                     0.2)
                                  (- (math.sqrt (+ (* x x) (* y y) (* z z))) 1)))}]}

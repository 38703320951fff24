;; expect: test/corpus/custom-lipschitz-too-small.fnl:3: objects[1].lipschitz: declares 1, but the distance changes by 6.92 per unit at [-0.4 0.4 0.4] (sampled over its bounds); declare at least 6.92, or leave :lipschitz out to have it measured
;; A gyroid declared 1-Lipschitz: its field changes faster; refused, not torn.
{:objects [{:kind :custom :bounds [1 1 1] :lipschitz 1
            :distance (fn [x y z]
                        (- (math.abs (+ (* (math.sin (* 4 x)) (math.cos (* 4 y)))
                                        (* (math.sin (* 4 y)) (math.cos (* 4 z)))
                                        (* (math.sin (* 4 z)) (math.cos (* 4 x)))))
                           0.2))}]}

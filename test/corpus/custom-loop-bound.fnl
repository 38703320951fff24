;; expect: test/corpus/custom-loop-bound.fnl:6: objects[1].distance: a for loop's bounds must be whole constant numbers, or a stop of (math.min n K) for at most K turns, K a whole constant (the shader needs a bound on the turns; a loop must end)
;; A for loop whose bound is a value of the point: it might never end on the GPU.
{:objects [{:kind :custom :bounds [1 1 1]
            :distance (fn [x y z]
                        (var d 0)
                        (for [i 1 (math.floor (* x 10))] (set d (+ d 1)))
                        (- d 1))}]}

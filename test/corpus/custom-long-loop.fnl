;; expect: test/corpus/custom-long-loop.fnl:6: objects[1].distance: a for loop may turn at most 64 times, this one turns 1000 times
;; A for loop of 1000 turns: more than a distance function may take.
{:objects [{:kind :custom :bounds [1 1 1]
            :distance (fn [x y z]
                        (var d 10)
                        (for [i 1 1000] (set d (math.min d (- (math.abs (- x (* i 0.01))) 0.1))))
                        d)}]}

;; expect: test/corpus/custom-recursion.fnl:5: objects[1].distance: `fold` calls itself: recursion is not supported in a distance function
;; A recursive helper.
{:objects [{:kind :custom :bounds [1 1 1]
            :distance (fn [x y z]
                        (fn fold [a n] (if (< n 1) a (fold (math.abs (- a 0.5)) (- n 1))))
                        (- (fold x 3) 0.2))}]}

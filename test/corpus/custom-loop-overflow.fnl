;; expect: test/corpus/custom-loop-overflow.fnl:6: objects[1].distance: a for loop's counter must stay within -16777216 to 16777216 (2^24: the shader counts in a 32-bit int, read as a float exact only so far), this one reaches 2147483648; count from a small number and add the rest in the body, like (for [i 0 3] (let [k (+ i 1000)] ...))
;; Three turns, but up to 2^31 - 1: the shader's int counter would wrap, never ending.
{:objects [{:kind :custom :bounds [1 1 1]
            :distance (fn [x y z]
                        (var d 10)
                        (for [i 2147483645 2147483647] (set d (math.min d (- (math.abs x) 0.5))))
                        d)}]}

;; expect: test/corpus/custom-index-range.fnl:8: objects[1].distance: the index may be 1 to 4, outside an array of 3 vectors of 3 numbers (items 1 to 3)
;; An array indexed past its end: the loop's counter reaches 4, the array has 3 items.
(local offsets [[0 0 1] [0 1 0] [1 0 0]])
{:objects [{:kind :custom :bounds [2 2 2]
            :distance (fn [x y z]
                        (var d 100)
                        (for [i 1 4]
                          (let [[ox oy oz] (. offsets i)]
                            (set d (math.min d (- (length [(- x ox) (- y oy) (- z oz)]) 0.5)))))
                        d)}]}

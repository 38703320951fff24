;; expect: test/corpus/custom-global.fnl:6: objects[1].distance: `tonumber` is not defined in the distance function (it may use its arguments, its own locals and helpers, math.*, and numbers or math functions named outside it)
;; A call to a function that is not math's nor a helper.
{:objects [{:kind :custom :bounds [1 1 1]
            :distance (fn [x y z]
                        (- (math.sqrt (+ (* x x) (* y y) (* z z)))
                           (tonumber "1")))}]}

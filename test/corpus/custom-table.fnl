;; expect: test/corpus/custom-table.fnl:5: objects[1].distance: a {...} table is not supported in a distance function (supported: numbers, vectors [a b c] and arrays of them, let, local, var/set, if, when, do, -> ->>, values, fn helpers, for with constant bounds, + - * / % ^, comparisons, and/or/not, math functions)
;; A table with keys built at run time inside a distance function ([x y z] is a vector).
{:objects [{:kind :custom :bounds [1 1 1]
            :distance (fn [x y z]
                        (let [p {:x x :y y :z z}]
                          (- (math.sqrt (+ (* x x) (* y y) (* z z))) 1)))}]}

;; expect: test/corpus/custom-table.fnl:5: objects[1].distance: a [...] table is not supported in a distance function (for several numbers use (values a b c); supported: numbers, let, local, var/set, if, when, do, -> ->>, values, fn helpers, for with constant bounds, + - * / % ^, comparisons, and/or/not, math functions)
;; A table built at run time inside a distance function.
{:objects [{:kind :custom :bounds [1 1 1]
            :distance (fn [x y z]
                        (let [p [x y z]]
                          (- (math.sqrt (+ (* x x) (* y y) (* z z))) 1)))}]}

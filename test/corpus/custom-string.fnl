;; expect: test/corpus/custom-string.fnl:4: objects[1].distance: a string is not supported in a distance function (supported: numbers, vectors [a b c] and arrays of them, let, local, var/set, if, when, do, -> ->>, values, fn helpers, for with constant bounds, + - * / % ^, comparisons, and/or/not, math functions)
;; A string inside a distance function.
{:objects [{:kind :custom :bounds [1 1 1]
            :distance (fn [x y z] (if (< x 0) "inside" 1))}]}

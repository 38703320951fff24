;; expect: test/corpus/custom-while.fnl:6: objects[1].distance: `while` is not supported in a distance function (use for with constant bounds; supported: numbers, vectors [a b c] and arrays of them, let, local, var/set, if, when, do, -> ->>, values, fn helpers, for with constant bounds, + - * / % ^, comparisons, and/or/not, math functions)
;; A distance function with a while loop: refused, the loop's line named.
{:objects [{:kind :custom :bounds [1 1 1]
            :distance (fn [x y z]
                        (var d 1)
                        (while (> d 0.5) (set d (* d 0.5)))
                        d)}]}

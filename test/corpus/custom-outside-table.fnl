;; expect: test/corpus/custom-outside-table.fnl:6: objects[1].distance: `sizes` is a table that is not an array of numbers or of vectors [a b] or [a b c] (it has no items 1, 2, ...); a distance function may use numbers, math functions, functions of the file and such arrays from outside it
;; A name from outside the function that holds a table with keys (an array of numbers
;; or of vectors may be used, and indexed).
(local sizes {:small 1 :large 3})
{:objects [{:kind :custom :bounds [1 1 1]
            :distance (fn [x y z] (- (math.abs x) sizes))}]}

;; expect: test/corpus/custom-outside-table.fnl:5: objects[1].distance: `sizes` is a table from outside the function; a distance function may use numbers and math functions from outside it
;; A name from outside the function that holds a table.
(local sizes [1 2 3])
{:objects [{:kind :custom :bounds [1 1 1]
            :distance (fn [x y z] (- (math.abs x) sizes))}]}

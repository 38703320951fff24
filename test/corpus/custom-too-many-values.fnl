;; expect: test/corpus/custom-too-many-values.fnl:4: objects[1].distance: a distance function must give one number, this one gives 2 values
;; A distance function that gives two values.
{:objects [{:kind :custom :bounds [1 1 1]
            :distance (fn [x y z] (values x y))}]}

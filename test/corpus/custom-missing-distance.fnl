;; expect: test/corpus/custom-missing-distance.fnl:3: objects[1].distance: must be a distance function like (fn [x y z] (- (math.sqrt (+ (* x x) (* y y) (* z z))) 1)), got 1
;; A custom node whose :distance is a number.
{:objects [{:kind :custom :bounds [1 1 1] :distance 1}]}

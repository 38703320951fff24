;; expect: test/corpus/custom-two-on-a-line.fnl:3: objects[1].distance: line 3 holds several functions with 3 parameters; put the distance function on a line of its own
;; Two functions of three parameters on one line: which one is the distance is unknown.
(local f (fn [x y z] (- (math.abs x) 1))) (local g (fn [x y z] (- (math.abs y) 1)))
{:objects [{:kind :custom :bounds [1 1 1] :distance g}]}

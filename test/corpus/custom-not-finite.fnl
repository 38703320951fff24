;; expect: test/corpus/custom-not-finite.fnl:4: objects[1].distance: gives a value that is not a finite number at [-1.4 -1.4 -1.4] (sampled over its bounds grown by half: it must give a number everywhere there)
;; A function that gives nan inside its bounds (the square root of a negative).
{:objects [{:kind :custom :bounds [1 1 1]
            :distance (fn [x y z] (- (math.sqrt x) 1))}]}

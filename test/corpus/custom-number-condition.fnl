;; expect: test/corpus/custom-number-condition.fnl:4: objects[1].distance: a condition must be a comparison like (< a b), or and/or/not of comparisons: a number is always true in Fennel and never in GLSL
;; A number used as a condition: always true in Fennel, a type error in GLSL.
{:objects [{:kind :custom :bounds [1 1 1]
            :distance (fn [x y z] (if x 1 (- z 1)))}]}

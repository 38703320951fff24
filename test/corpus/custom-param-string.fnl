;; expect: test/corpus/custom-param-string.fnl:3: objects[1].params.radius: must be a number from -1e7 to 1e7, got "big"
;; A parameter that is not a number.
{:objects [{:kind :custom :bounds [1 1 1] :params {:radius "big"}
            :distance (fn [x y z radius]
                        (- (math.sqrt (+ (* x x) (* y y) (* z z))) radius))}]}

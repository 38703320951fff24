;; expect: test/corpus/custom-param-unused.fnl:3: objects[1].params.radios: is not a parameter of the distance function; name it after x y z: (fn [x y z radius radios] ...)
;; :params names a value the function does not take.
{:objects [{:kind :custom :bounds [1 1 1] :params {:radius 1 :radios 2}
            :distance (fn [x y z radius]
                        (- (math.sqrt (+ (* x x) (* y y) (* z z))) radius))}]}

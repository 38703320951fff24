;; expect: test/corpus/custom-vector-sizes.fnl:5: objects[1].distance: (+ ...) mixes a vector of 3 numbers with one of 2; make them one size: [(. v 1) (. v 2)] is two of three
;; Vectors of two sizes added: a vec3 point and a vec2 offset.
{:objects [{:kind :custom :bounds [1 1 1]
            :distance (fn [p]
                        (- (length (+ p [0.5 0.5])) 1))}]}

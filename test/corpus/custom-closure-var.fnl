;; expect: test/corpus/custom-closure-var.fnl:6: objects[1].distance: a helper function sets `best` of the function around it: closures over mutable state are not supported
;; A helper that sets a var of the function around it: a closure over mutable state.
{:objects [{:kind :custom :bounds [1 1 1]
            :distance (fn [x y z]
                        (var best 10)
                        (fn try [d] (set best (math.min best d)) d)
                        (try (- (math.abs x) 1))
                        best)}]}

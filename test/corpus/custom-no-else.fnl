;; expect: test/corpus/custom-no-else.fnl:5: objects[1].distance: an if needs an else branch (the last argument): a distance has a value everywhere
;; An if without an else: nil where the condition fails.
{:objects [{:kind :custom :bounds [1 1 1]
            :distance (fn [x y z]
                        (if (> z 0)
                            (- (math.sqrt (+ (* x x) (* y y) (* z z))) 1)))}]}

;; expect: test/corpus/custom-param-missing.fnl:4: objects[1].distance: its parameter `height` has no value: add it to :params, like :params {:height 1}
;; The function takes a parameter :params does not give.
{:objects [{:kind :custom :bounds [1 1 1] :params {:radius 1}
            :distance (fn [x y z radius height]
                        (- (math.sqrt (+ (* x x) (* y y) (* z z))) radius))}]}

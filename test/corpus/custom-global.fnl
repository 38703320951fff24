;; expect: test/corpus/custom-global.fnl:6: objects[1].distance: `tonumber` is not a function a distance function may call (it may call math.sqrt abs floor ceil sin cos tan asin acos atan exp log pow min max and GLSL's clamp mix fract sign step smoothstep round mod length dot cross normalize as math.clamp ..., and helper functions: (fn name [a b] ...) in the function or the file)
;; A call to a function that is not math's nor a helper.
{:objects [{:kind :custom :bounds [1 1 1]
            :distance (fn [x y z]
                        (- (math.sqrt (+ (* x x) (* y y) (* z z)))
                           (tonumber "1")))}]}

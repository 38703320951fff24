;; expect: test/corpus/custom-math-random.fnl:4: objects[1].distance: `math.fmod` is not one of the math functions a distance function may use; for a remainder write (% a b) or (math.mod a b), floored as GLSL's mod (math.fmod truncates toward zero)
;; A math function that is not one of the supported ones.
{:objects [{:kind :custom :bounds [1 1 1]
            :distance (fn [x y z] (- (math.abs x) (math.fmod y 1)))}]}

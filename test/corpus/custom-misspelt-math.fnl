;; expect: test/corpus/custom-misspelt-math.fnl:4: objects[1].distance: `math.smothstep` is not one of the math functions a distance function may use; did you mean math.smoothstep? (it may use math.sqrt abs floor ceil sin cos tan asin acos atan exp log pow min max, GLSL's clamp mix fract sign step smoothstep round mod, of vectors length dot cross normalize, and math.pi huge)
;; A misspelt GLSL function: the message guesses the name meant.
{:objects [{:kind :custom :bounds [1 1 1]
            :distance (fn [x y z] (- (math.abs x) (math.smothstep 0 1 y)))}]}

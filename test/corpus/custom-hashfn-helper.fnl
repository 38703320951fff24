;; expect: test/corpus/custom-hashfn-helper.fnl:5: objects[1].distance: `fract` is a function the translator cannot read: it has no (fn ...) form in the scene file (a #(...) has none); write it (fn fract [a b] ...); or call math.fract, GLSL's fract
;; A helper of the file written #(...): no form to translate; GLSL's fract exists.
(local fract #(- $ (math.floor $)))
{:objects [{:kind :custom :bounds [1 1 1]
            :distance (fn [x y z] (- (math.abs x) (fract y)))}]}

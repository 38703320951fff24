;; expect: test/corpus/custom-missing-bounds.fnl:3: objects[1].bounds: missing; a custom node needs :bounds [hx hy hz], the half extents of a box about its origin that holds the shape
;; A custom node without :bounds.
{:objects [{:kind :custom
            :distance (fn [x y z] (- (math.sqrt (+ (* x x) (* y y) (* z z))) 1))}]}

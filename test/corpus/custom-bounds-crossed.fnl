;; expect: test/corpus/custom-bounds-crossed.fnl:5: objects[1].bounds: the distance is -0.134 at (0.625, -0.625, 0) outside the box, so the shape lies beyond its bounds [0.5 0.5 0.1]; a box that holds it: [1.3 1.3 0.25]
;; A torus of radius 1 (tube 0.25) in bounds that hold only its hole: the renderer
;; takes the box's distance outside the box, so the torus would never be drawn.
{:objects [{:kind :custom
            :bounds [0.5 0.5 0.1]
            :distance (fn [x y z]
                        (let [q (- (math.sqrt (+ (* x x) (* y y))) 1)]
                          (- (math.sqrt (+ (* q q) (* z z))) 0.25)))}]}

;; expect: test/corpus/inf-draw-distance.fnl:2: render.draw-distance: must be a positive number from 1e-6 to 1e7, got inf
{:render {:draw-distance (/ 1 0)}
 :objects []}

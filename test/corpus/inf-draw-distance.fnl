;; expect: test/corpus/inf-draw-distance.fnl:2: render.draw-distance: must be a positive number, got inf
{:render {:draw-distance (/ 1 0)}
 :objects []}

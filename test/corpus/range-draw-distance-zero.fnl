;; expect: test/corpus/range-draw-distance-zero.fnl:2: render.draw-distance: must be a positive number from 1e-6 to 1e7, got 0
{:render {:draw-distance 0}
 :objects []}

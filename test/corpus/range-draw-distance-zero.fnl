;; expect: test/corpus/range-draw-distance-zero.fnl:2: render.draw-distance: must be a positive number, got 0
{:render {:draw-distance 0}
 :objects []}

;; expect: test/corpus/range-draw-distance-huge.fnl:2: render.draw-distance: must be a positive number from 1e-6 to 1e7, got 1e+30
{:render {:draw-distance 1e30}
 :objects []}

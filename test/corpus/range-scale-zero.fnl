;; expect: test/corpus/range-scale-zero.fnl:2: render.scale: must be a render scale above 0 and at most 1, got 0
{:render {:scale 0}
 :objects []}

;; expect: test/corpus/range-scale-two.fnl:2: render.scale: must be a render scale above 0 and at most 1, got 2
{:render {:scale 2}
 :objects []}

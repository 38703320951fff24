;; expect: test/corpus/range-max-steps-huge-int.fnl:2: render.max-steps: must be an integer from 1 to 100000, got 9.007199254741e+15
{:render {:max-steps 9007199254740993}
 :objects []}

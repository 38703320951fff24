;; expect: test/corpus/range-max-steps-zero.fnl:2: render.max-steps: must be an integer from 1 to 100000, got 0
{:render {:max-steps 0}
 :objects []}

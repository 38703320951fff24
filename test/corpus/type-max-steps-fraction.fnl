;; expect: test/corpus/type-max-steps-fraction.fnl:2: render.max-steps: must be an integer from 1 to 100000, got 1.5
{:render {:max-steps 1.5}
 :objects []}

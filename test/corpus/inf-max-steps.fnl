;; expect: test/corpus/inf-max-steps.fnl:2: render.max-steps: must be an integer from 1 to 100000, got inf
{:render {:max-steps (/ 1 0)}
 :objects []}

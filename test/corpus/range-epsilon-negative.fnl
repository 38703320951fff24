;; expect: test/corpus/range-epsilon-negative.fnl:2: render.epsilon: must be a number from 0 to 10, got -0.0001
{:render {:epsilon -1e-4}
 :objects []}

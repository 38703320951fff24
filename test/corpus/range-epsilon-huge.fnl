;; expect: test/corpus/range-epsilon-huge.fnl:2: render.epsilon: must be a number from 0 to 10, got 1000000
{:render {:epsilon 1e6}
 :objects []}

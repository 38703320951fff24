;; expect: test/corpus/nan-epsilon.fnl:2: render.epsilon: must be a number from 0 to 10, got nan
{:render {:epsilon (/ 0 0)}
 :objects []}

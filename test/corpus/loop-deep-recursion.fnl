;; expect: test/corpus/loop-deep-recursion.fnl: stack overflow
(fn deep [n] (+ 1 (deep (+ n 1))))
(deep 0)
{:objects []}

;; expect: test/corpus/loop-tail-recursion.fnl: the scene ran for more than 10 million steps and was stopped (an endless loop?)
(fn spin [n] (spin (+ n 1)))
(spin 0)
{:objects []}

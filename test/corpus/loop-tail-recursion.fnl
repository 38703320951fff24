;; expect: test/corpus/loop-tail-recursion.fnl: the scene ran for more than 20 million steps and was stopped (an endless loop?)
(fn spin [n] (spin (+ n 1)))
(spin 0)
{:objects []}

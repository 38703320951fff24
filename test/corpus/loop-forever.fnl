;; expect: test/corpus/loop-forever.fnl: the scene ran for more than 1 s and was stopped (an endless loop?)
(while true)
{:objects []}

;; expect: test/corpus/loop-forever.fnl: the scene ran for more than 10 million steps and was stopped (an endless loop?)
(while true)
{:objects []}

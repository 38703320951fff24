;; expect: test/corpus/loop-forever.fnl: the scene ran for more than 20 million steps and was stopped (an endless loop?)
(while true)
{:objects []}

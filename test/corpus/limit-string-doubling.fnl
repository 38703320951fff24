;; expect: test/corpus/limit-string-doubling.fnl: the scene built more than 512 MB of data and was stopped
(var s "x")
(for [i 1 40] (set s (.. s s)))
{:name s :objects []}

;; expect: test/corpus/forbidden-string-dump.fnl:2: attempt to call field 'dump' (a nil value)
{:name (string.dump (fn [] 1))
 :objects []}

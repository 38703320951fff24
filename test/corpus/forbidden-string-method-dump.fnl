;; expect: test/corpus/forbidden-string-method-dump.fnl:2: attempt to call field 'dump' (a nil value)
{:name ((. "" :dump) (fn [] 1))
 :objects []}

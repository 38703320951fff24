;; expect: test/corpus/limit-huge-string-separator.fnl:2: string.rep: the result would be over 1 MB
{:name (string.rep "" 100000 (string.rep "x" 1000))
 :objects []}

;; expect: test/corpus/limit-huge-string.fnl:2: string.rep: the result would be over 1 MB
{:name (string.rep "x" 1e9)
 :objects []}

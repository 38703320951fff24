;; expect: test/corpus/limit-huge-string-method.fnl:2: string.rep: the result would be over 1 MB
{:name (: "x" :rep 2e8)
 :objects []}

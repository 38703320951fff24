;; expect: test/corpus/limit-format-method.fnl:2: string.format: the result would be over 1 MB
{:objects []
 :name (: "%s%s%s" :format (string.rep "y" 500000) (string.rep "y" 500000) "z")}

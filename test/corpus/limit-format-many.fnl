;; expect: test/corpus/limit-format-many.fnl:3: string.format: the result would be over 1 MB
{:objects []
 :name (string.format (string.rep "%s" 50) (unpack (fcollect [i 1 50] (string.rep "y" 100000))))}

;; expect: test/corpus/limit-rep-number-separator.fnl:3: string.rep: the result would be over 1 MB
;; A number as the separator.
{:objects [{:kind :sphere :radius (length (string.rep "x" 700000 12345))}]}

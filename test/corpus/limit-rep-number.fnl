;; expect: test/corpus/limit-rep-number.fnl:3: string.rep: the result would be over 1 MB
;; A number as the string to repeat (Lua turns it into one).
{:objects [{:kind :sphere :radius (length (string.rep 7 2000000000))}]}

;; expect: test/corpus/syntax-bad-string.fnl:4:0: Parse error: expected closing delimiters }"
{:name "never closed
 :objects [{:kind :sphere :radius 1}]}

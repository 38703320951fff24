;; expect: test/corpus/syntax-unclosed.fnl:4:0: Parse error: expected closing delimiter }
{:name "unclosed"
 :objects [{:kind :sphere :radius 1}]

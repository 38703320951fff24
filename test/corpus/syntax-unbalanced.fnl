;; expect: test/corpus/syntax-unbalanced.fnl:3:38: Parse error: unexpected closing delimiter }
{:name "unbalanced"
 :objects [{:kind :sphere :radius 1}]}}

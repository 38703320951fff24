;; expect: test/corpus/syntax-mismatched.fnl:3:36: Parse error: mismatched closing delimiter }, expected ]
{:name "mismatched"
 :objects [{:kind :sphere :radius 1}}]

;; expect: test/corpus/syntax-odd-table.fnl:3:33: Parse error: expected even number of values in table literal
{:name "odd"
 :objects [{:kind :sphere :radius}]}

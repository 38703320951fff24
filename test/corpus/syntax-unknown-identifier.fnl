;; expect: test/corpus/syntax-unknown-identifier.fnl:3:18: Compile error: unknown identifier: sphere (scene files are data: only math, numbers, strings and tables are available)
{:name "bare word"
 :objects [{:kind sphere :radius 1}]}

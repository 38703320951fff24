;; expect: test/corpus/object-number.fnl:2: objects[2]: must be a table like {:kind :sphere ...}, got 42
{:objects [{:kind :sphere :radius 1}
           42]}

;; expect: test/corpus/type-name-number.fnl:2: name: must be a string, got 42
{:name 42
 :objects []}

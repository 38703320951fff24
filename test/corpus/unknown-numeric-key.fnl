;; expect: test/corpus/unknown-numeric-key.fnl:2: unexpected entry 1; fields are named, like :name
{1 2
 :objects []}

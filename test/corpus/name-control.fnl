;; expect: test/corpus/name-control.fnl:2: name: must be a line of UTF-8 text of at most 80 bytes, got "two\nlines"
{:name "two\nlines"
 :objects []}

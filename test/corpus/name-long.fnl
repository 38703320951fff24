;; expect: test/corpus/name-long.fnl:2: name: must be a line of UTF-8 text of at most 80 bytes, got a string of 81 bytes
{:name (string.rep "n" 81)
 :objects []}

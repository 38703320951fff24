;; expect: test/corpus/name-not-utf8.fnl:2: name: must be a line of UTF-8 text of at most 80 bytes, got "\255\254 scene"
{:name "\255\254 scene"
 :objects []}

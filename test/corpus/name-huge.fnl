;; expect: test/corpus/name-huge.fnl:3: name: must be a line of UTF-8 text of at most 80 bytes, got a string of 10000000 bytes
(let [s (string.rep "n" 1000000)]
  {:name (.. s s s s s s s s s s)
   :objects []})

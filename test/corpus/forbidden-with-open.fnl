;; expect: test/corpus/forbidden-with-open.fnl:2: (with-open ...) is not allowed: scene files are data and run no compile-time code
(with-open [f (io.open "/etc/passwd")] {:objects []})

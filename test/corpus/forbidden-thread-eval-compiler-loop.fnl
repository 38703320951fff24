;; expect: test/corpus/forbidden-thread-eval-compiler-loop.fnl:3: (eval-compiler ...) is not allowed: scene files are data and run no compile-time code
;; An endless loop at compile time, built by ->> after the first-word check.
{:objects (->> (while true nil) eval-compiler)}

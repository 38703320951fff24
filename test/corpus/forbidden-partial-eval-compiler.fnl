;; expect: test/corpus/forbidden-partial-eval-compiler.fnl:3: (eval-compiler ...) is not allowed: scene files are data and run no compile-time code
;; partial builds (fn [...] (eval-compiler (while true nil) ...)): a loop at compile time.
{:objects [] :name (partial eval-compiler (while true nil))}

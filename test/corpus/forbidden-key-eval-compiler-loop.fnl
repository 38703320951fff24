;; expect: test/corpus/forbidden-key-eval-compiler-loop.fnl:2: (eval-compiler ...) is not allowed: scene files are data and run no compile-time code
{(eval-compiler (while true nil)) 1
 :objects []}

;; expect: test/corpus/forbidden-eval-compiler.fnl:2: (eval-compiler ...) is not allowed: scene files are data and run no compile-time code
(eval-compiler
  (os.execute "touch test/out/corpus-trace/eval-compiler"))
{:objects []}

;; expect: test/corpus/forbidden-binding-eval-compiler.fnl:2: (eval-compiler ...) is not allowed: scene files are data and run no compile-time code
(let [x (eval-compiler (os.execute "touch test/out/corpus-trace/binding"))]
  {:objects []})

;; expect: test/corpus/forbidden-thread-require-macros.fnl:3: (require-macros ...) is not allowed: scene files are data and run no compile-time code
;; -> builds (require-macros ...), which loads and runs a module inside the compiler.
(-> :test.support.fields require-macros)
{:objects []}

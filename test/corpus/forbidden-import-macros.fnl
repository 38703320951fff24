;; expect: test/corpus/forbidden-import-macros.fnl:2: (import-macros ...) is not allowed: scene files are data and run no compile-time code
(import-macros m :test.corpus.evil)
{:objects []}

;; expect: test/corpus/forbidden-key-require-macros.fnl:2: (require-macros ...) is not allowed: scene files are data and run no compile-time code
{(require-macros :x) 1 :objects []}

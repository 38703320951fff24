;; expect: test/corpus/forbidden-key-import-macros.fnl:3: (import-macros ...) is not allowed: scene files are data and run no compile-time code
{:objects []
 (import-macros m :x) 1}

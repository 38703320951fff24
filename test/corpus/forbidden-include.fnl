;; expect: test/corpus/forbidden-include.fnl:2: (include ...) is not allowed: scene files are data and run no compile-time code
(include :src.png)
{:objects []}

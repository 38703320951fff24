;; expect: test/corpus/forbidden-key-include.fnl:2: (include ...) is not allowed: scene files are data and run no compile-time code
{(include :src.scene) 1 :objects []}

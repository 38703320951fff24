;; expect: test/corpus/forbidden-key-global.fnl:2: (global ...) is not allowed: scene files are data and set no globals
{(global trace 1) 1 :objects []}

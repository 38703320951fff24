;; expect: test/corpus/forbidden-global.fnl:2: (global ...) is not allowed: scene files are data and set no globals
(global x 1)
{:objects []}

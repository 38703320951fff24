;; expect: test/corpus/forbidden-thread-global.fnl:3: (global ...) is not allowed: scene files are data and set no globals
;; partial builds (fn [...] (global boom 1 ...)): a global set after the first-word check.
((partial global boom 1))
{:objects []}

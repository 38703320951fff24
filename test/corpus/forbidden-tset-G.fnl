;; expect: test/corpus/forbidden-tset-G.fnl:2:6: Compile error: unknown identifier: _G (scene files are data: only math, numbers, strings and tables are available)
(tset _G :io nil)
{:objects []}

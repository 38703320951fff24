;; expect: test/corpus/forbidden-setfenv.fnl:2:1: Compile error: unknown identifier: setfenv (scene files are data: only math, numbers, strings and tables are available)
(setfenv 1 {})
{:objects []}

;; expect: test/corpus/forbidden-debug-getinfo.fnl:2:1: Compile error: unknown identifier: debug (scene files are data: only math, numbers, strings and tables are available)
(debug.getinfo 1)
{:objects []}

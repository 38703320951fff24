;; expect: test/corpus/forbidden-dofile.fnl:2:1: Compile error: unknown identifier: dofile (scene files are data: only math, numbers, strings and tables are available)
(dofile "main.lua")
{:objects []}

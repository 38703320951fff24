;; expect: test/corpus/forbidden-loadfile.fnl:2:2: Compile error: unknown identifier: loadfile (scene files are data: only math, numbers, strings and tables are available)
((loadfile "main.lua"))
{:objects []}

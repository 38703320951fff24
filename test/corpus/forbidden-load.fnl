;; expect: test/corpus/forbidden-load.fnl:2:2: Compile error: unknown identifier: load (scene files are data: only math, numbers, strings and tables are available)
((load "io.open('test/out/corpus-trace/load', 'w')"))
{:objects []}

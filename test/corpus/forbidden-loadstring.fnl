;; expect: test/corpus/forbidden-loadstring.fnl:2:2: Compile error: unknown identifier: loadstring (scene files are data: only math, numbers, strings and tables are available)
((loadstring "io.open('test/out/corpus-trace/loadstring', 'w')"))
{:objects []}

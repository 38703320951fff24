;; expect: test/corpus/forbidden-getfenv.fnl:2:10: Compile error: unknown identifier: getfenv (scene files are data: only math, numbers, strings and tables are available)
(local g (getfenv 0))
(g.io.open "test/out/corpus-trace/getfenv" "w")
{:objects []}

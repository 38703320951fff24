;; expect: test/corpus/forbidden-collectgarbage.fnl:2:1: Compile error: unknown identifier: collectgarbage (scene files are data: only math, numbers, strings and tables are available)
(collectgarbage :stop)
{:objects []}

;; expect: test/corpus/forbidden-rawget.fnl:2:10: Compile error: unknown identifier: rawget (scene files are data: only math, numbers, strings and tables are available)
(local m (rawget _ENV :io))
{:objects []}

;; expect: test/corpus/forbidden-rawset.fnl:2:1: Compile error: unknown identifier: rawset (scene files are data: only math, numbers, strings and tables are available)
(rawset math :pi 3)
{:objects []}

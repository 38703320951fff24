;; expect: test/corpus/forbidden-print.fnl:2:1: Compile error: unknown identifier: print (scene files are data: only math, numbers, strings and tables are available)
(print "hello")
{:objects []}

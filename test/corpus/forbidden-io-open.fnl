;; expect: test/corpus/forbidden-io-open.fnl:2:8: Compile error: unknown identifier: io (scene files are data: only math, numbers, strings and tables are available)
{:name (io.open "test/out/corpus-trace/io-open" "w")
 :objects []}

;; expect: test/corpus/forbidden-io-popen.fnl:2:8: Compile error: unknown identifier: io (scene files are data: only math, numbers, strings and tables are available)
{:name (io.popen "touch test/out/corpus-trace/io-popen")
 :objects []}

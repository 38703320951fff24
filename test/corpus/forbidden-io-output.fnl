;; expect: test/corpus/forbidden-io-output.fnl:2:1: Compile error: unknown identifier: io (scene files are data: only math, numbers, strings and tables are available)
(io.output "test/out/corpus-trace/io-output")
{:objects []}

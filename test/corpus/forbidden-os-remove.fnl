;; expect: test/corpus/forbidden-os-remove.fnl:2:1: Compile error: unknown identifier: os (scene files are data: only math, numbers, strings and tables are available)
(os.remove "test/out/corpus-sentinel")
{:objects []}

;; expect: test/corpus/forbidden-os-rename.fnl:2:1: Compile error: unknown identifier: os (scene files are data: only math, numbers, strings and tables are available)
(os.rename "test/out/corpus-sentinel" "test/out/corpus-trace/os-rename")
{:objects []}

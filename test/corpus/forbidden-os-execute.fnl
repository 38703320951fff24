;; expect: test/corpus/forbidden-os-execute.fnl:2:1: Compile error: unknown identifier: os (scene files are data: only math, numbers, strings and tables are available)
(os.execute "touch test/out/corpus-trace/os-execute")
{:objects []}

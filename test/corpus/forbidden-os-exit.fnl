;; expect: test/corpus/forbidden-os-exit.fnl:2:1: Compile error: unknown identifier: os (scene files are data: only math, numbers, strings and tables are available)
(os.exit 3)
{:objects []}

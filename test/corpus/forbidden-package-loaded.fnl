;; expect: test/corpus/forbidden-package-loaded.fnl:2:11: Compile error: unknown identifier: package (scene files are data: only math, numbers, strings and tables are available)
(local io2 package.loaded.io)
(io2.open "test/out/corpus-trace/package-loaded" "w")
{:objects []}

;; expect: test/corpus/forbidden-require-ffi.fnl:2:12: Compile error: unknown identifier: require (scene files are data: only math, numbers, strings and tables are available)
(local ffi (require :ffi))
(ffi.C.system "touch test/out/corpus-trace/ffi")
{:objects []}

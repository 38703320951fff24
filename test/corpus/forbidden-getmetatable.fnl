;; expect: test/corpus/forbidden-getmetatable.fnl:2:11: Compile error: unknown identifier: getmetatable (scene files are data: only math, numbers, strings and tables are available)
(local mt (getmetatable ""))
{:objects []}

;; expect: test/corpus/forbidden-setmetatable.fnl:2:1: Compile error: unknown identifier: setmetatable (scene files are data: only math, numbers, strings and tables are available)
(setmetatable {} {:__gc (fn [] nil)})
{:objects []}

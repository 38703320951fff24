;; expect: test/corpus/forbidden-set-G.fnl:2:5: Compile error: expected local _G (scene files are data: only math, numbers, strings and tables are available)
(set _G.x 1)
{:objects []}

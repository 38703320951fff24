;; expect: test/corpus/forbidden-love.fnl:2:1: Compile error: unknown identifier: love (scene files are data: only math, numbers, strings and tables are available)
(love.filesystem.write "corpus-trace" "x")
{:objects []}

;; expect: test/corpus/forbidden-require.fnl:2:10: Compile error: unknown identifier: require (scene files are data: only math, numbers, strings and tables are available)
(local f (require :src.png))
{:objects []}

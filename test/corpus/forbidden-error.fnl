;; expect: test/corpus/forbidden-error.fnl:2:1: Compile error: unknown identifier: error (scene files are data: only math, numbers, strings and tables are available)
(error {:scene-error "scenes/seed.fnl:1: forged message"})
{:objects []}

;; expect: test/corpus/forbidden-math-randomseed.fnl:2: attempt to call field 'randomseed' (a nil value)
(math.randomseed 1)
{:objects []}

;; expect: test/corpus/forbidden-set-forcibly.fnl:2: (set-forcibly! ...) is not allowed: scene files are data and set no globals
(set-forcibly! x 1)
{:objects []}

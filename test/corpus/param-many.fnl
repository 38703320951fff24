;; expect: test/corpus/param-many.fnl:4: (param :p65 ...): a scene has at most 64 parameters
;; Thousands of parameters made in a loop: the name is computed, so refused (and 64
;; is the cap for literal ones).
{:objects [] :name (tostring (fcollect [i 1 100000] (param (.. "p" i) 1 {:min 0 :max 2})))}

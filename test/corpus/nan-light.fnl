;; expect: test/corpus/nan-light.fnl:2: light.pos[1]: must be a number from -1e7 to 1e7, got nan
{:light {:pos [(/ 0 0) 0 0]}
 :objects []}

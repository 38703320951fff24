;; expect: test/corpus/nan-light.fnl:2: light.pos[1]: must be a finite number, got nan
{:light {:pos [(/ 0 0) 0 0]}
 :objects []}

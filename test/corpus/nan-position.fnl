;; expect: test/corpus/nan-position.fnl:3: objects[1].pos[1]: must be a finite number, got nan
{:objects [{:kind :sphere
            :pos [(/ 0 0) 0 0]}]}

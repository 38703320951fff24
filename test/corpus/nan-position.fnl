;; expect: test/corpus/nan-position.fnl:3: objects[1].pos[1]: must be a number from -1e7 to 1e7, got nan
{:objects [{:kind :sphere
            :pos [(/ 0 0) 0 0]}]}

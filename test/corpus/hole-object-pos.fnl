;; expect: test/corpus/hole-object-pos.fnl:3: objects[1].pos[1]: must be a number from -1e7 to 1e7, got nil
{:objects [{:kind :sphere
            :pos [nil nil 1]}]}

;; expect: test/corpus/inf-position.fnl:3: objects[1].pos[2]: must be a number from -1e7 to 1e7, got inf
{:objects [{:kind :box
            :pos [0 (/ 1 0) 0]}]}

;; expect: test/corpus/type-pos-two-numbers.fnl:3: objects[1].pos: must be a list of three numbers like [1 2 3], got a list of 2 items
{:objects [{:kind :sphere
            :pos [1 2]}]}

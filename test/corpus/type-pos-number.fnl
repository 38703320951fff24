;; expect: test/corpus/type-pos-number.fnl:3: objects[1].pos: must be a list of three numbers like [1 2 3], got 5
{:objects [{:kind :sphere
            :pos 5}]}

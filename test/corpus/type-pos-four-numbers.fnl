;; expect: test/corpus/type-pos-four-numbers.fnl:3: objects[1].pos: must be a list of three numbers like [1 2 3], got a list of 4 items
{:objects [{:kind :box
            :pos [1 2 3 4]}]}

;; expect: test/corpus/negative-size.fnl:3: objects[1].size[2]: must be three positive numbers like [1 1 1], got -1
{:objects [{:kind :box
            :size [1 -1 1]}]}

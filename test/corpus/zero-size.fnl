;; expect: test/corpus/zero-size.fnl:3: objects[1].size[1]: must be three positive numbers like [1 1 1], got 0
{:objects [{:kind :box
            :size [0 1 1]}]}

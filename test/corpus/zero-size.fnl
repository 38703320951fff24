;; expect: test/corpus/zero-size.fnl:3: objects[1].size[1]: must be a positive number from 1e-6 to 1e7, got 0
{:objects [{:kind :box
            :size [0 1 1]}]}

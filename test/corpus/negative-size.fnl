;; expect: test/corpus/negative-size.fnl:3: objects[1].size[2]: must be a positive number from 1e-6 to 1e7, got -1
{:objects [{:kind :box
            :size [1 -1 1]}]}

;; expect: test/corpus/range-size-tiny.fnl:2: objects[1].size[2]: must be a positive number from 1e-6 to 1e7, got 1e-09
{:objects [{:kind :box :size [1 1e-9 1]}]}

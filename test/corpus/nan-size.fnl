;; expect: test/corpus/nan-size.fnl:3: objects[1].size[3]: must be a positive number from 1e-6 to 1e7, got nan
{:objects [{:kind :box
            :size [1 1 (/ 0 0)]}]}

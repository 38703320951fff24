;; expect: test/corpus/nan-size.fnl:3: objects[1].size[3]: must be three positive numbers like [1 1 1], got nan
{:objects [{:kind :box
            :size [1 1 (/ 0 0)]}]}

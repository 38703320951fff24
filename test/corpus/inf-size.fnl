;; expect: test/corpus/inf-size.fnl:3: objects[1].size[1]: must be three positive numbers like [1 1 1], got inf
{:objects [{:kind :box
            :size [(/ 1 0) 1 1]}]}

;; expect: test/corpus/inf-size.fnl:3: objects[1].size[1]: must be a positive number from 1e-6 to 1e7, got inf
{:objects [{:kind :box
            :size [(/ 1 0) 1 1]}]}

;; expect: test/corpus/type-size-boolean.fnl:3: objects[1].size: must be three positive numbers like [1 1 1], got true
{:objects [{:kind :box
            :size true}]}

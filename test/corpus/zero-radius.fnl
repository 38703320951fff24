;; expect: test/corpus/zero-radius.fnl:3: objects[1].radius: must be a positive number, got 0
{:objects [{:kind :sphere
            :radius 0}]}

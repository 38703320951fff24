;; expect: test/corpus/type-radius-string.fnl:3: objects[1].radius: must be a positive number from 1e-6 to 1e7, got "2"
{:objects [{:kind :sphere
            :radius "2"}]}

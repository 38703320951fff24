;; expect: test/corpus/type-radius-string.fnl:3: objects[1].radius: must be a positive number, got "2"
{:objects [{:kind :sphere
            :radius "2"}]}

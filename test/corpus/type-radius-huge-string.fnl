;; expect: test/corpus/type-radius-huge-string.fnl:3: objects[1].radius: must be a positive number, got a string of 100000 characters
{:objects [{:kind :sphere
            :radius (string.rep "x" 100000)}]}

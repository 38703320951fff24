;; expect: test/corpus/type-radius-huge-string.fnl:3: objects[1].radius: must be a positive number from 1e-6 to 1e7, got a string of 100000 bytes
{:objects [{:kind :sphere
            :radius (string.rep "x" 100000)}]}

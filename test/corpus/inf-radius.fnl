;; expect: test/corpus/inf-radius.fnl:3: objects[1].radius: must be a positive number, got inf
{:objects [{:kind :sphere
            :radius (/ 1 0)}]}

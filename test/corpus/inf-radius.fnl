;; expect: test/corpus/inf-radius.fnl:3: objects[1].radius: must be a positive number from 1e-6 to 1e7, got inf
{:objects [{:kind :sphere
            :radius (/ 1 0)}]}

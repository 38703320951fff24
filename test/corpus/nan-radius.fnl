;; expect: test/corpus/nan-radius.fnl:3: objects[1].radius: must be a positive number from 1e-6 to 1e7, got nan
{:objects [{:kind :sphere
            :radius (/ 0 0)}]}

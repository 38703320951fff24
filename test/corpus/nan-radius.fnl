;; expect: test/corpus/nan-radius.fnl:3: objects[1].radius: must be a positive number, got nan
{:objects [{:kind :sphere
            :radius (/ 0 0)}]}

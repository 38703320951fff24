;; expect: test/corpus/range-radius-huge.fnl:3: objects[1].radius: must be a positive number from 1e-6 to 1e7, got 1e+308
{:objects [{:kind :sphere
            :radius 1e308}]}

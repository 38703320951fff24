;; expect: test/corpus/neg-inf-height.fnl:3: objects[1].height: must be a number from -1e7 to 1e7, got -inf
{:objects [{:kind :plane
            :height (/ -1 0)}]}

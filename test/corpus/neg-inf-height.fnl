;; expect: test/corpus/neg-inf-height.fnl:3: objects[1].height: must be a finite number, got -inf
{:objects [{:kind :plane
            :height (/ -1 0)}]}

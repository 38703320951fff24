;; expect: test/corpus/tree-param-check.fnl:3: objects[1].radius: must be less than half the smallest :size (0.5)
{:objects [{:kind :round-box :size [1 1 1]
            :radius 0.8}]}

;; expect: test/corpus/tree-rotate-zero-axis.fnl:2: objects[1].axis: must be a direction, not all zero, got [0 0 0]
{:objects [{:kind :rotate :axis [0 0 0] :angle 30
            :children [{:kind :box}]}]}

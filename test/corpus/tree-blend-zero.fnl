;; expect: test/corpus/tree-blend-zero.fnl:2: objects[1].radius: must be a positive number from 1e-6 to 1e7, got 0
{:objects [{:kind :chamfer-union :radius 0
            :children [{:kind :sphere} {:kind :box}]}]}

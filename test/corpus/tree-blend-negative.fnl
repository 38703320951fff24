;; expect: test/corpus/tree-blend-negative.fnl:4: objects[1].children[1].radius: must be a positive number from 1e-6 to 1e7, got -0.5
{:objects [{:kind :union
            :children [{:kind :smooth-union
                        :radius -0.5
                        :children [{:kind :sphere} {:kind :box}]}]}]}

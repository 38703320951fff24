;; expect: test/corpus/tree-kernel-unknown.fnl:2: objects[1].kernel: must be one of :poly :exp, got :expo (did you mean :exp?)
{:objects [{:kind :smooth-union :radius 0.2 :kernel :expo
            :children [{:kind :sphere} {:kind :box}]}]}

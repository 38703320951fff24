;; expect: test/corpus/tree-repeat-zero-period.fnl:3: objects[1].period: must be above 0 along at least one axis (0 leaves an axis unrepeated)
{:objects [{:kind :repeat
            :period [0 0 0]
            :children [{:kind :sphere}]}]}

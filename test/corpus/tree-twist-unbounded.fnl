;; expect: test/corpus/tree-twist-unbounded.fnl:2: objects[1]: :twist needs a child bounded in x and y (its Lipschitz factor grows with the child's size)
{:objects [{:kind :twist :angle 20
            :children [{:kind :cylinder :radius 1}
                       ]}]}

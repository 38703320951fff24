;; expect: test/corpus/tree-too-few-children.fnl:3: objects[1].children: :subtraction takes 2 or more children, got 1
{:objects [{:kind :subtraction
            :children [{:kind :box}]}]}

;; expect: test/corpus/tree-too-many-children.fnl:3: objects[1].children: :twist takes exactly 1 child, got 2
{:objects [{:kind :twist :angle 10
            :children [{:kind :box} {:kind :sphere}]}]}

;; expect: test/corpus/tree-material-color.fnl:4: objects[1].children[2].color[1]: must be a colour of three numbers from 0 to 1, got 1.5
{:objects [{:kind :union
            :children [{:kind :sphere}
                       {:kind :box :color [1.5 0 0]}]}]}

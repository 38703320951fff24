;; expect: test/corpus/tree-unknown-child-kind.fnl:4: objects[1].children[2].kind: unknown kind :toruss (did you mean :torus?) (`love . --kinds` lists them all)
{:objects [{:kind :union
            :children [{:kind :sphere}
                       {:kind :toruss :radius 1}]}]}

;; expect: test/corpus/tree-too-many-nodes.fnl:3: objects[1].children[250].children[1]: the scene has more than 500 tree nodes
{:objects [{:kind :union
            :children (fcollect [i 1 300]
                        {:kind :round :radius 0.1 :children [{:kind :sphere :pos [i 0 0]}]})}]}

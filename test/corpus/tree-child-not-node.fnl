;; expect: test/corpus/tree-child-not-node.fnl:3: objects[1].children[2]: must be a node table like {:kind :sphere ...}, got 42
{:objects [{:kind :union
            :children [{:kind :sphere} 42]}]}

;; expect: test/corpus/tree-children-named.fnl:2: objects[1].children: must be a list [...] of nodes, not a table with named fields
{:objects [{:kind :union :children {:a {:kind :sphere}}}]}

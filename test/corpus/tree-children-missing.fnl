;; expect: test/corpus/tree-children-missing.fnl:2: objects[1].children: must be a list of 2 or more nodes, got nil
{:objects [{:kind :smooth-union :radius 0.5}]}

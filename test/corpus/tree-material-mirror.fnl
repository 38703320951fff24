;; expect: test/corpus/tree-material-mirror.fnl:3: objects[1].mirror: must be a number from 0 to 1, got 2
{:objects [{:kind :torus
            :mirror 2}]}

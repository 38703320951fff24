;; expect: test/corpus/kind-number.fnl:2: objects[1].kind: must be a kind name like :sphere, got 1
{:objects [{:kind 1 :radius 1}]}

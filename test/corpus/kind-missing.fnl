;; expect: test/corpus/kind-missing.fnl:3: objects[2]: missing :kind (see `love . --kinds` for the list)
{:objects [{:kind :sphere :radius 1}
           {:radius 2 :pos [0 0 3]}]}

;; expect: test/corpus/kind-missing.fnl:3: objects[2]: missing :kind; one of :sphere :box :plane
{:objects [{:kind :sphere :radius 1}
           {:radius 2 :pos [0 0 3]}]}

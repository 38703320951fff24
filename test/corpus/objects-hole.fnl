;; expect: test/corpus/objects-hole.fnl:3: objects[2]: must be a table like {:kind :sphere ...}, got nil
{:objects [{:kind :sphere :radius 1}
           nil
           {:kind :box :size [1 1 1]}]}

;; expect: test/corpus/hole-color.fnl:2: objects[1].color[1]: must be a colour of three numbers from 0 to 1, got nil
{:objects [{:kind :sphere :color [nil 1 1]}
           {:kind :sphere :color [1 0 0]}]}

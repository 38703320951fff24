;; expect: test/corpus/color-above-one.fnl:3: objects[1].color[2]: must be a colour of three numbers from 0 to 1, got 1.5
{:objects [{:kind :sphere
            :color [1 1.5 1]}]}

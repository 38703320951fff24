;; expect: test/corpus/nan-color.fnl:3: objects[1].color[2]: must be a colour of three numbers from 0 to 1, got nan
{:objects [{:kind :sphere
            :color [0 (/ 0 0) 0]}]}

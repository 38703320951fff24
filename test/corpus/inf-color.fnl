;; expect: test/corpus/inf-color.fnl:3: objects[1].color[1]: must be a colour of three numbers from 0 to 1, got inf
{:objects [{:kind :plane
            :color [(/ 1 0) 0 0]}]}

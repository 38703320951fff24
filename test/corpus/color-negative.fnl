;; expect: test/corpus/color-negative.fnl:3: objects[1].color[1]: must be a colour of three numbers from 0 to 1, got -0.1
{:objects [{:kind :plane
            :color [-0.1 0 0]}]}

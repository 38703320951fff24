;; expect: test/corpus/color-255.fnl:3: objects[1].color[1]: must be a colour of three numbers from 0 to 1, got 255
{:objects [{:kind :box
            :color [255 128 0]}]}

;; expect: test/corpus/type-color-string.fnl:3: objects[1].color: must be a colour of three numbers from 0 to 1, got "red"
{:objects [{:kind :box
            :color "red"}]}

;; expect: test/corpus/type-pos-element-string.fnl:3: objects[1].pos[2]: must be a number from -1e7 to 1e7, got "2"
{:objects [{:kind :sphere
            :pos [1 "2" 3]}]}

;; expect: test/corpus/type-pos-named-fields.fnl:3: objects[1].pos: must be a list of three numbers like [1 2 3], got a table
{:objects [{:kind :sphere
            :pos {:x 1 :y 2 :z 3}}]}

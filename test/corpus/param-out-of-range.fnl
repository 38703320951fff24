;; expect: test/corpus/param-out-of-range.fnl:4: (param :radius ...): the value 9 is outside :min 0.5 :max 3
{:objects [{:kind :sphere
            :pos [0 0 1]
            :radius (param :radius 9 {:min 0.5 :max 3})}]}

;; expect: test/corpus/param-function-value.fnl:2: (param :spin ...): the value must be a number, true or false, or three numbers like [1 0.5 0.2]
{:objects [{:kind :torus :thickness (param :spin (fn [t] t) {:min 0 :max 1})}]}

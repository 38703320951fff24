;; expect: test/corpus/anim-out-of-range.fnl:3: objects[1].children[1].radius: must be a positive number from 1e-6 to 1e7, got -1
{:objects [{:kind :union
            :children [{:kind :sphere :radius (fn [t] (- t 1))}]}]}

;; expect: test/corpus/anim-fails.fnl:3: objects[1].thickness: the function of time failed at t = 0: test/corpus/anim-fails.fnl:3: attempt to index field 'missing' (a nil value)
{:objects [{:kind :torus
            :thickness (fn [t] (. (. {} :missing) 1))}]}

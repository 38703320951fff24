;; expect: test/corpus/anim-loop.fnl:3: objects[1].radius: the function of time failed at t = 0: test/corpus/anim-loop.fnl: the scene ran for more than 100000 steps and was stopped (an endless loop?)
{:objects [{:kind :sphere
            :radius (fn [t] (while true nil) 1)}]}

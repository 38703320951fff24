;; expect: test/corpus/custom-time-no-range.fnl:4: objects[1].params.r: a function of time; declare the values it takes, like :ranges {:r [0.5 2]}, so that the distance's factor holds for all of them
;; A custom parameter moved by a function of time without :ranges: its factor would be
;; measured at t = 0 only.
{:objects [{:kind :custom :bounds [1 1 1] :params {:r (fn [t] (+ 1 (* 0.5 (math.sin t))))}
            :distance (fn [x y z r] (* r (- (math.sqrt (+ (* x x) (* y y) (* z z))) 1)))}]}

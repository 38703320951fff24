;; Statistics of timings and other samples, for the app's reports (the player's
;; refinement message, --bench, --soak) and the checks'.

(fn median [xs]
  "Median of the numbers `xs` (nil when empty); `xs` is not modified."
  (let [s (icollect [_ x (ipairs xs)] x)
        n (length s)]
    (table.sort s)
    (if (= n 0) nil
        (= (% n 2) 1) (. s (/ (+ n 1) 2))
        (/ (+ (. s (/ n 2)) (. s (+ (/ n 2) 1))) 2))))

{: median}

;; expect: test/corpus/anim-insert-position.fnl:3: objects[1].radius: the function of time failed at t = 0: test/corpus/anim-insert-position.fnl:3: table.insert: position -2147483647 is out of bounds (1 to 1)
;; The same C loop in a function of time.
{:objects [{:kind :sphere :radius (fn [t] (table.insert [] -2147483647 1) 1)}]}

;; expect: test/corpus/limit-insert-position.fnl:3: table.insert: position -2147483647 is out of bounds (1 to 1)
;; One C loop of two billion steps that no step counter sees.
{:objects [{:kind :sphere :radius (do (table.insert [] -2147483647 1) 1)}]}

;; expect: test/corpus/scene-list.fnl:2: a scene file must evaluate to a table like {:objects [...]}, got a list of 1 items
[{:kind :sphere :radius 1}]

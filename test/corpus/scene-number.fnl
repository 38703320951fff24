;; expect: test/corpus/scene-number.fnl: a scene file must evaluate to a table like {:objects [...]}, got 42
42

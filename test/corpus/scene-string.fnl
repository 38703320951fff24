;; expect: test/corpus/scene-string.fnl: a scene file must evaluate to a table like {:objects [...]}, got "a scene"
"a scene"

;; expect: test/corpus/scene-empty-file.fnl: a scene file must evaluate to a table like {:objects [...]}, got nil

;; expect: test/corpus/type-reflections-string.fnl:2: render.reflections: must be an integer from 0 to 16, got "3"
{:render {:reflections "3"}
 :objects []}

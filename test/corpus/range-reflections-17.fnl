;; expect: test/corpus/range-reflections-17.fnl:2: render.reflections: must be an integer from 0 to 16, got 17
{:render {:reflections 17}
 :objects []}

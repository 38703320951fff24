;; expect: test/corpus/range-reflections-negative.fnl:2: render.reflections: must be an integer from 0 to 16, got -1
{:render {:reflections -1}
 :objects []}

;; expect: test/corpus/nan-reflections.fnl:2: render.reflections: must be an integer from 0 to 16, got nan
{:render {:reflections (/ 0 0)}
 :objects []}

;; expect: test/corpus/nan-relaxation.fnl:2: render.relaxation: must be an over-relaxation factor from 1 up to (not including) 2, got nan
{:render {:relaxation (/ 0 0)}
 :objects []}

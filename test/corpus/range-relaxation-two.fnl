;; expect: test/corpus/range-relaxation-two.fnl:2: render.relaxation: must be an over-relaxation factor from 1 up to (not including) 2, got 2
{:render {:relaxation 2}
 :objects []}

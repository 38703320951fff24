;; expect: test/corpus/choice-hit-test-transposed.fnl:2: render.hit-test: must be one of :fixed :relative :pixel, got :pixle (did you mean :pixel?)
{:render {:hit-test :pixle}
 :objects []}

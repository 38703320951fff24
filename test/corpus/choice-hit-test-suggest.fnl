;; expect: test/corpus/choice-hit-test-suggest.fnl:2: render.hit-test: must be one of :fixed :relative :pixel, got :pixal (did you mean :pixel?)
{:render {:hit-test :pixal}
 :objects []}

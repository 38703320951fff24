;; expect: test/corpus/type-shadows-number.fnl:2: render.shadows: must be true or false, got 1
{:render {:shadows 1}
 :objects []}

;; expect: test/corpus/type-glow-string.fnl:2: render.glow: must be true or false, got "yes"
{:render {:glow "yes"}
 :objects []}

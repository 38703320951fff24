;; expect: test/corpus/nan-scale.fnl:2: render.scale: must be a render scale above 0 and at most 1, got nan
{:render {:scale (/ 0 0)}
 :objects []}

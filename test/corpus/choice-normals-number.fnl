;; expect: test/corpus/choice-normals-number.fnl:2: render.normals: must be one of :one-sided :central :tetrahedron, got 3
{:render {:normals 3}
 :objects []}

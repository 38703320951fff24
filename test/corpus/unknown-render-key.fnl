;; expect: test/corpus/unknown-render-key.fnl:2: render.reflection: unknown field (did you mean :reflections?); known fields: :adaptive :bounds :draw-distance :epsilon :glow :hit-test :max-steps :normals :normals-of :out-of-steps :reflections :relaxation :samples :scale :shadows
{:render {:reflection 2}
 :objects []}

;; expect: test/corpus/unknown-key-suggest.fnl:3: objects[1].radus: unknown field (did you mean :radius?); known fields: :color :emission :kind :mirror :pos :radius :rotate :roughness :scale
{:objects [{:kind :sphere
            :radus 2}]}

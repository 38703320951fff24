;; expect: test/corpus/tree-child-field-suggest.fnl:4: objects[1].children[2].radus: unknown field (did you mean :radius?); known fields: :color :emission :height :kind :mirror :pos :radius :rotate :roughness :scale
{:objects [{:kind :intersection
            :children [{:kind :sphere :radius 1}
                       {:kind :capped-cylinder :radus 1}]}]}

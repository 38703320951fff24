;; expect: test/corpus/unknown-key-no-suggestion.fnl:3: objects[1].wobble: unknown field; known fields: :color :emission :kind :mirror :pos :rotate :roughness :scale :size
{:objects [{:kind :box
            :wobble 2}]}

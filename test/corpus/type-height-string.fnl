;; expect: test/corpus/type-height-string.fnl:3: objects[1].height: must be a finite number, got "0"
{:objects [{:kind :plane
            :height "0"}]}

;; expect: test/corpus/type-height-string.fnl:3: objects[1].height: must be a number from -1e7 to 1e7, got "0"
{:objects [{:kind :plane
            :height "0"}]}

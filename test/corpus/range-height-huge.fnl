;; expect: test/corpus/range-height-huge.fnl:2: objects[1].height: must be a number from -1e7 to 1e7, got -1000000000
{:objects [{:kind :plane :height -1e9}]}

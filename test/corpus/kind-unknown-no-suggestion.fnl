;; expect: test/corpus/kind-unknown-no-suggestion.fnl:2: objects[1].kind: unknown kind :teapot (`love . --kinds` lists them all)
{:objects [{:kind :teapot :radius 2}]}

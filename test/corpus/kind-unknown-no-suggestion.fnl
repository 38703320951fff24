;; expect: test/corpus/kind-unknown-no-suggestion.fnl:2: objects[1].kind: unknown kind :torus; known kinds: :sphere :box :plane
{:objects [{:kind :torus :radius 2}]}

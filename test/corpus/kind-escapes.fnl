;; expect: test/corpus/kind-escapes.fnl:2: objects[1].kind: unknown kind "\027[2Jsphere"; known kinds: :sphere :box :plane
{:objects [{:kind "\27[2Jsphere"}]}

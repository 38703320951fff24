;; expect: test/corpus/kind-escapes.fnl:2: objects[1].kind: unknown kind "\027[2Jsphere" (`love . --kinds` lists them all)
{:objects [{:kind "\27[2Jsphere"}]}

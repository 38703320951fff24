;; expect: test/corpus/kind-huge.fnl:2: objects[1].kind: unknown kind "ssssssssssssssssssssssssssssssssssssssss"... (1000000 bytes) (`love . --kinds` lists them all)
{:objects [{:kind (string.rep "s" 1000000)}]}

;; expect: test/corpus/kind-unknown-suggest.fnl:3: objects[2].kind: unknown kind :sphre (did you mean :sphere?) (`love . --kinds` lists them all)
{:objects [{:kind :sphere :radius 1}
           {:kind :sphre :radius 2}]}

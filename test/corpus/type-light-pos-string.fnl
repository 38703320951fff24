;; expect: test/corpus/type-light-pos-string.fnl:2: light.pos: must be a list of three numbers like [1 2 3], got "up"
{:light {:pos "up"}
 :objects []}

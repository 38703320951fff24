;; expect: test/corpus/param-hostile-options.fnl:3: (param :r ...): the options must be a table like {:min 0 :max 1}
;; Options that are not a table, from code: refused with the parameter's name.
{:objects [{:kind :sphere :radius (param :r 1 (string.rep "x" 1000))}]}

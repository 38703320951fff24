;; expect: test/corpus/type-render-list.fnl:2: render: must be a table like {:adaptive ...}, got a list of 3 items
{:render [1 2 3]
 :objects []}

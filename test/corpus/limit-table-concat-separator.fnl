;; expect: test/corpus/limit-table-concat-separator.fnl:2: table.concat: the result would be over 1 MB
{:objects []
 :name (table.concat [1 2 3] (string.rep "-" 1000000))}

;; expect: test/corpus/limit-table-concat.fnl:3: table.concat: the result would be over 1 MB
{:objects []
 :name (table.concat (fcollect [i 1 1500] (string.rep "x" 1000000)))}

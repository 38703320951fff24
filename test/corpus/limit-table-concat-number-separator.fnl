;; expect: test/corpus/limit-table-concat-number-separator.fnl:3: table.concat: the result would be over 1 MB
;; A number as the separator of 400,000 empty strings: 8 MB in one call.
{:objects [] :name (table.concat (fcollect [i 1 400000] "") 1.2345678901234567e-300)}

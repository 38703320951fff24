;; expect: test/corpus/limit-huge-table.fnl: the scene built more than 512 MB of data and was stopped
{:objects (fcollect [i 1 1e8] {:kind :sphere})}

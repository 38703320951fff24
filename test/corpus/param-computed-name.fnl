;; expect: test/corpus/param-computed-name.fnl:4: (param ...): the name must be written as a keyword like :radius
;; A name computed in code could not be found in the file to save it.
{:objects (fcollect [i 1 3]
            {:kind :sphere :pos [(* 3 i) 0 1] :radius (param (.. "r" i) 1 {:min 0.5 :max 2})})}

;; expect: test/corpus/limit-object-count.fnl:2: objects: has 1000001 objects; at most 1000000 are allowed (remove 1)
{:objects (fcollect [i 1 1000001]
           {:kind :plane :height (- i)})}

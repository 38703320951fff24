;; expect: test/corpus/limit-object-count.fnl:2: objects: has 200001 objects; at most 200000 are allowed (remove 1)
{:objects (fcollect [i 1 200001]
           {:kind :plane :height (- i)})}

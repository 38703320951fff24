;; expect: test/corpus/limit-object-count.fnl:2: objects: has 5001 objects; at most 5000 are allowed
{:objects (fcollect [i 1 5001]
           {:kind :plane :height (- i)})}

;; expect: test/corpus/tree-too-many-nodes.fnl: objects[1]: the shader would hold 601 tree nodes written out, more than 500 (compiling grows faster than their number); this object writes 601 of them. Objects of one structure (the same kinds and fields, other numbers) share one loop: make more of them alike, or remove some
;; (Children of two structures: a union of children all alike would be one loop.)
{:objects [{:kind :union
            :children (fcollect [i 1 300]
                        {:kind :round :radius 0.1
                         :children [(if (= 0 (% i 2)) {:kind :sphere :pos [i 0 0]} {:kind :box :pos [i 0 0]})]})}]}

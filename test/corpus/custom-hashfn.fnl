;; expect: test/corpus/custom-hashfn.fnl:4: objects[1].distance: must be written (fn [x y z] ...) in the scene file (a #(...) has no form to translate)
;; A distance function written #(...): its form has no named point.
{:objects [{:kind :custom :bounds [1 1 1]
            :distance #(- (math.abs $1) 1)}]}

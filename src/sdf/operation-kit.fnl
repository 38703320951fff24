;; What several operations' descriptors (src/sdf/operations/) share: their classes
;; and bounds from their children's, and angles.

(local {: floor : max : pi} math)

(fn round [v] (floor (+ v 0.5)))

(fn rad [deg] (* deg (/ pi 180)))

(fn all-exact [_ children]
  (var exact? true)
  (each [_ c (ipairs children)] (when (not= c.class :exact) (set exact? false)))
  (if exact? :exact :bound))

(fn first-class [_ children] (. children 1 :class))

(fn bound-class [] :bound)

(fn first-bounds [_ children] (. children 1 :bounds))

(fn merge-bounds [_ children]
  (var out [0 0 0])
  (each [_ c (ipairs children) &until (= out nil)]
    (if c.bounds
        (let [[x y z] c.bounds [ox oy oz] out]
          (set out [(max x ox) (max y oy) (max z oz)]))
        (set out nil)))
  out)

(fn grow-bounds [b by]
  (when b (let [[x y z] b] [(+ x by) (+ y by) (+ z by)])))

{: round : rad : all-exact : first-class : bound-class : first-bounds : merge-bounds : grow-bounds}

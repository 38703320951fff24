;; Round box: exact. A box of full extents :size whose edges and corners are rounded by
;; :radius: the exact distance to the box shrunk by :radius on every side, less :radius
;; (an offset of an exact distance is exact outside), so the outer extents stay :size.
(local {: min} math)

{:kind :round-box
 :doc "Box with full extents :size, edges and corners rounded by :radius."
 :params [{:name :size :type :size3 :default [1 1 1]}
          {:name :radius :type :length0 :default 0.1}]
 :check (fn [o]
          (let [[x y z] o.size
                half (* 0.5 (min x y z))]
            (when (>= o.radius half)
              (values :radius (string.format "must be less than half the smallest :size (%g)"
                                             half)))))
 :class :exact
 ;; Even in each coordinate and never decreasing as its size grows (see :even in
 ;; src/sdf/primitives.fnl): a centred copy in a repetition is the nearest one.
 :even [true true true]
 :args [{:name :b :type :vec3} {:name :r :type :float}]
 :pack (fn [o]
         (let [[x y z] o.size r o.radius]
           [(- (* x 0.5) r) (- (* y 0.5) r) (- (* z 0.5) r) r]))
 :glsl-name "sdRoundBox"
 ;; The distance once, in Fennel: src/sdf/translate.fnl writes :glsl and :cpu from it.
 :fennel "(fn [x y z bx by bz r]
  (let [qx (- (math.abs x) bx) qy (- (math.abs y) by) qz (- (math.abs z) bz)
        ox (math.max qx 0) oy (math.max qy 0) oz (math.max qz 0)]
    (- (+ (math.sqrt (+ (* ox ox) (* oy oy) (* oz oz)))
          (math.min (math.max qx qy qz) 0))
       r)))"
 :bounds (fn [o] (let [[x y z] o.size] [(* x 0.5) (* y 0.5) (* z 0.5)]))}

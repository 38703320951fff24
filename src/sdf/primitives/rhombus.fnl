;; Rhombus (a rounded rhombic slab): exact. The rhombus in the xy plane with
;; half-diagonals :length-a along x and :length-b along y, grown by :radius, extruded to
;; :height along z. Folded into the first quadrant, the nearest point of the edge from
;; (a, 0) to (0, b) has parameter f in [-1, 1] (the ndot form of the projection); the
;; signed 2D distance less the rounding is extruded like a box.

{:kind :rhombus
 :doc "Rhombic slab: half-diagonals :length-a (x) and :length-b (y), :height (z), edges rounded by :radius."
 :params [{:name :length-a :type :positive :default 0.8}
          {:name :length-b :type :positive :default 0.5}
          {:name :height :type :positive :default 0.3}
          {:name :radius :type :length0 :default 0.05}]
 :class :exact
 :args [{:name :b :type :vec2} {:name :h :type :float} {:name :r :type :float}]
 :pack (fn [o] [o.length-a o.length-b (* o.height 0.5) o.radius])
 :glsl-name "sdRhombus"
 ;; The distance once, in Fennel: src/sdf/translate.fnl writes :glsl and :cpu from it.
 :fennel "(fn [x y z ba bb h r]
  (let [x (math.abs x) y (math.abs y) z (math.abs z)
        f (math.max -1 (math.min 1 (/ (- (* ba (- ba (* 2 x))) (* bb (- bb (* 2 y))))
                                      (+ (* ba ba) (* bb bb)))))
        ex (- x (* 0.5 ba (- 1 f))) ey (- y (* 0.5 bb (+ 1 f)))
        w (- (+ (* x bb) (* y ba)) (* ba bb))
        sg (if (> w 0) 1 (< w 0) -1 0)
        qx (- (* (math.sqrt (+ (* ex ex) (* ey ey))) sg) r)
        qy (- z h)
        ox (math.max qx 0) oy (math.max qy 0)]
    (+ (math.min (math.max qx qy) 0) (math.sqrt (+ (* ox ox) (* oy oy))))))"
 :bounds (fn [o] [(+ o.length-a o.radius) (+ o.length-b o.radius) (* o.height 0.5)])}

;; Capped cylinder: exact. In the plane through the z axis and the point, the shape is a
;; rectangle (:radius by half the :height), so this is the 2D box distance there.

{:kind :capped-cylinder
 :doc "Cylinder along z of :radius and full :height."
 :params [{:name :radius :type :positive :default 0.5}
          {:name :height :type :positive :default 1}]
 :class :exact
 ;; Even in each coordinate and never decreasing as its size grows (see :even in
 ;; src/sdf/primitives.fnl): a centred copy in a repetition is the nearest one.
 :even [true true true]
 :args [{:name :r :type :float} {:name :h :type :float}]
 :pack (fn [o] [o.radius (* o.height 0.5)])
 :glsl-name "sdCappedCylinder"
 ;; The distance once, in Fennel: src/sdf/translate.fnl writes :glsl and :cpu from it.
 :fennel "(fn [x y z r h]
  (let [dx (- (math.sqrt (+ (* x x) (* y y))) r)
        dy (- (math.abs z) h)
        ox (math.max dx 0) oy (math.max dy 0)]
    (+ (math.min (math.max dx dy) 0) (math.sqrt (+ (* ox ox) (* oy oy))))))"
 :bounds (fn [o] [o.radius o.radius (* o.height 0.5)])}

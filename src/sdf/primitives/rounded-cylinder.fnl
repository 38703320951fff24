;; Rounded cylinder: exact. A capped cylinder shrunk by :rounding on every side, whose
;; exact distance less :rounding rounds both rims; the outer :radius and :height stay.

{:kind :rounded-cylinder
 :doc "Cylinder along z of :radius and full :height, rims rounded by :rounding."
 :params [{:name :radius :type :positive :default 0.5}
          {:name :height :type :positive :default 1}
          {:name :rounding :type :length0 :default 0.1}]
 :check (fn [o]
          (if (>= o.rounding o.radius)
              (values :rounding (string.format "must be less than :radius (%g)" o.radius))
              (>= o.rounding (* o.height 0.5))
              (values :rounding (string.format "must be less than half the :height (%g)"
                                               (* o.height 0.5)))))
 :class :exact
 ;; Even in each coordinate and never decreasing as its size grows (see :even in
 ;; src/sdf/primitives.fnl): a centred copy in a repetition is the nearest one.
 :even [true true true]
 :args [{:name :ra :type :float} {:name :h :type :float} {:name :rb :type :float}]
 :pack (fn [o] [(- o.radius o.rounding) (- (* o.height 0.5) o.rounding) o.rounding])
 :glsl-name "sdRoundedCylinder"
 ;; The distance once, in Fennel: src/sdf/translate.fnl writes :glsl and :cpu from it.
 :fennel "(fn [x y z ra h rb]
  (let [dx (- (math.sqrt (+ (* x x) (* y y))) ra)
        dy (- (math.abs z) h)
        ox (math.max dx 0) oy (math.max dy 0)]
    (- (+ (math.min (math.max dx dy) 0) (math.sqrt (+ (* ox ox) (* oy oy)))) rb)))"
 :bounds (fn [o] [o.radius o.radius (* o.height 0.5)])}

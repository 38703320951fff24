;; Death star: exact. A ball of :radius at the origin with a ball of :cutter-radius,
;; centred :offset up the z axis, carved out of it. In the plane q = (p.z, |p.xy|) the
;; two circles cross at the rim (a, b). Points in the wedge at the rim between the ray
;; from the origin through the rim (continued outwards) and the ray from the rim towards
;; the cutter's centre are nearest the rim; elsewhere max(sphere, -cutter) is exact.
(local {: sqrt : max : abs} math)

(fn rim [o]
  "The rim circle of the carved edge: (a, b) = its height and radius."
  (let [ra o.radius rb o.cutter-radius d o.offset
        a (/ (+ (- (* ra ra) (* rb rb)) (* d d)) (* 2 d))]
    (values a (sqrt (max (- (* ra ra) (* a a)) 0)))))

{:kind :death-star
 :doc "Ball of :radius with a ball of :cutter-radius, :offset up the z axis, carved out."
 :params [{:name :radius :type :positive :default 1}
          {:name :cutter-radius :type :positive :default 0.6}
          {:name :offset :type :positive :default 1.1}]
 :check (fn [o]
          (let [lo (abs (- o.radius o.cutter-radius)) hi (+ o.radius o.cutter-radius)]
            (when (not (< lo o.offset hi))
              (values :offset (.. "must lie strictly between |:radius - :cutter-radius| and"
                                  " :radius + :cutter-radius (" lo " and " hi ")")))))
 :class :exact
 :args [{:name :ra :type :float} {:name :rb :type :float} {:name :d :type :float}
        {:name :rim :type :vec2}]
 :pack (fn [o] (let [(a b) (rim o)] [o.radius o.cutter-radius o.offset a b]))
 :glsl-name "sdDeathStar"
 ;; The distance once, in Fennel: src/sdf/translate.fnl writes :glsl and :cpu from it.
 :fennel "(fn [x y z ra rb d a b]
  (let [qx z qy (math.sqrt (+ (* x x) (* y y)))]
    (if (> (- (* qx b) (* qy a)) (* d (math.max (- b qy) 0)))
        (let [dx (- qx a) dy (- qy b)] (math.sqrt (+ (* dx dx) (* dy dy))))
        (let [dx (- qx d)]
          (math.max (- (math.sqrt (+ (* qx qx) (* qy qy))) ra)
                    (- rb (math.sqrt (+ (* dx dx) (* qy qy)))))))))"
 :bounds (fn [o] [o.radius o.radius o.radius])}

;; Capped torus (an arc of a torus): exact. The arc of the ring of :radius in the xy
;; plane that spans :angle degrees either side of the +y axis, thickened by :thickness:
;; the distance to the arc (to the ring where the point's direction lies inside the
;; arc's angle, else to the nearer end point), less the tube radius. A point on the -y
;; axis goes to the end point: that is the right choice at :angle 0 (a sphere), where
;; the angle test cannot tell, and the same distance as the ring's at 180.

{:kind :capped-torus
 :doc "Arc of a torus around z: ring :radius, tube radius :thickness, :angle degrees either side of +y (180: whole)."
 :params [{:name :radius :type :positive :default 1}
          {:name :thickness :type :positive :default 0.25}
          {:name :angle :type :degrees :min 0 :max 180 :default 120}]
 :check (fn [o]
          (when (>= o.thickness o.radius)
            (values :thickness (string.format "must be less than :radius (%g)" o.radius))))
 :class :exact
 ;; e: the arc's end point in the first quadrant, :radius * (sin, cos) of :angle.
 :args [{:name :e :type :vec2} {:name :ra :type :float} {:name :rb :type :float}]
 :pack (fn [o]
         (let [a (math.rad o.angle)]
           [(* o.radius (math.sin a)) (* o.radius (math.cos a)) o.radius o.thickness]))
 :glsl-name "sdCappedTorus"
 ;; The distance once, in Fennel: src/sdf/translate.fnl writes :glsl and :cpu from it.
 :fennel "(fn [x y z ex ey ra rb]
  (let [ax (math.abs x)]
    (- (if (or (> (* ey ax) (* ex y)) (and (= ax 0) (< y 0)))
           (let [dx (- ax ex) dy (- y ey)] (math.sqrt (+ (* dx dx) (* dy dy) (* z z))))
           (let [dr (- (math.sqrt (+ (* ax ax) (* y y))) ra)] (math.sqrt (+ (* dr dr) (* z z)))))
       rb)))"
 :bounds (fn [o]
           (let [r o.radius t o.thickness
                 wide (if (>= o.angle 90) 1 (math.sin (math.rad o.angle)))]
             [(+ (* r wide) t) (+ r t) t]))}

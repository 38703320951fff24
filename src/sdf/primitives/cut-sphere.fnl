;; Cut sphere: exact. The ball of :radius less everything above the plane z = :cut:
;; a sphere sliced flat on top, the flat face a disc of radius w = sqrt(r^2 - cut^2).
;; Worked in the meridian plane q = (|p.xy|, -p.z), flipped so that the kept part lies
;; above the flat face at height h = -cut. The arc is nearest when s < 0: q is past the
;; line from the centre through the rim (w, h) and past the parabola of points as far
;; from the arc as from the flat face; otherwise the flat face (q.x < w) or the rim.
(local {: sqrt} math)

{:kind :cut-sphere
 :doc "Sphere of :radius with the part above z = :cut sliced off flat."
 :params [{:name :radius :type :positive :default 1}
          {:name :cut :type :number :default 0.5}]
 :check (fn [o]
          (when (not (< (- o.radius) o.cut o.radius))
            (values :cut (.. "must lie strictly between -:radius and :radius ("
                             (- o.radius) " and " o.radius ")"))))
 :class :exact
 :args [{:name :r :type :float} {:name :h :type :float} {:name :w :type :float}]
 :pack (fn [o] [o.radius (- o.cut) (sqrt (- (* o.radius o.radius) (* o.cut o.cut)))])
 :glsl-name "sdCutSphere"
 ;; The distance once, in Fennel: src/sdf/translate.fnl writes :glsl and :cpu from it.
 :fennel "(fn [x y z r h w]
  (let [qx (math.sqrt (+ (* x x) (* y y))) qy (- z)
        s (math.max (+ (* (- h r) qx qx) (* w w (- (+ h r) (* 2 qy))))
                    (- (* h qx) (* w qy)))]
    (if (< s 0) (- (math.sqrt (+ (* qx qx) (* qy qy))) r)
        (< qx w) (- h qy)
        (let [dx (- qx w) dy (- qy h)] (math.sqrt (+ (* dx dx) (* dy dy)))))))"
 :bounds (fn [o]
           (let [e (if (> o.cut 0) o.radius (sqrt (- (* o.radius o.radius) (* o.cut o.cut))))]
             [e e o.radius]))}

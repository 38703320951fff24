;; Solid angle (a spherical sector, like an ice-cream cone): exact. The part of the ball
;; of :radius within :angle of the +z axis, apex at the origin. In the meridian plane
;; q = (|p.xy|, p.z) the outline is the arc and the segment from the origin to the rim
;; c r, c = (sin, cos) of the angle: outside the cone the segment (and its end, the rim)
;; is nearest, inside it the arc.
(local {: sin : cos : rad} math)

{:kind :solid-angle
 :doc "Spherical sector: the ball of :radius within :angle degrees of the +z axis."
 :params [{:name :angle :type :degrees :min 0 :max 180 :default 30}
          {:name :radius :type :positive :default 1}]
 :class :exact
 :args [{:name :c :type :vec2} {:name :r :type :float}]
 :pack (fn [o] (let [a (rad o.angle)] [(sin a) (cos a) o.radius]))
 :glsl-name "sdSolidAngle"
 ;; The distance once, in Fennel: src/sdf/translate.fnl writes :glsl and :cpu from it.
 :fennel "(fn [x y z cs cc r]
  (let [qx (math.sqrt (+ (* x x) (* y y))) qy z
        l (- (math.sqrt (+ (* qx qx) (* qy qy))) r)
        t (math.max 0 (math.min r (+ (* qx cs) (* qy cc))))
        mx (- qx (* cs t)) my (- qy (* cc t))
        m (math.sqrt (+ (* mx mx) (* my my)))
        w (- (* cc qx) (* cs qy))
        sg (if (> w 0) 1 (< w 0) -1 0)]
    (math.max l (* m sg))))"
 :bounds (fn [o]
           (let [e (if (< o.angle 90) (* o.radius (sin (rad o.angle))) o.radius)]
             [e e o.radius]))}

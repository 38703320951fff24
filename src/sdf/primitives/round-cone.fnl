;; Round cone: exact. The convex hull of a sphere of :radius1 at z = -:height/2 and one
;; of :radius2 at z = +:height/2. In the plane through the z axis and the point, the
;; hull's edge is the two circles joined by their common tangent line; along that line
;; the point is nearest the bottom circle, the tangent line or the top circle.
(local {: sqrt : max : abs} math)

{:kind :round-cone
 :doc "Round cone along z: spheres of :radius1 (bottom) and :radius2 (top) :height apart, and the cone joining them."
 :params [{:name :radius1 :type :length0 :default 0.5}
          {:name :radius2 :type :length0 :default 0.25}
          {:name :height :type :positive :default 1}]
 :check (fn [o]
          (if (and (<= o.radius1 0) (<= o.radius2 0))
              (values :radius1 "must be positive when :radius2 is 0")
              (<= o.height (abs (- o.radius1 o.radius2)))
              (values :height (string.format "must be more than the difference of the radii (%g)"
                                             (abs (- o.radius1 o.radius2))))))
 :class :exact
 ;; ab: (a, b), the unit normal of the tangent line in the (radial, z) plane, with
 ;; b = (r1 - r2) / height; hh: half the height.
 :args [{:name :ab :type :vec2} {:name :hh :type :float}
        {:name :r1 :type :float} {:name :r2 :type :float}]
 :pack (fn [o]
         (let [b (/ (- o.radius1 o.radius2) o.height)]
           [(sqrt (- 1 (* b b))) b (* o.height 0.5) o.radius1 o.radius2]))
 :glsl-name "sdRoundCone"
 ;; The distance once, in Fennel: src/sdf/translate.fnl writes :glsl and :cpu from it.
 :fennel "(fn [x y z a b hh r1 r2]
  (let [qx (math.sqrt (+ (* x x) (* y y)))
        m (+ (* qx (- b)) (* z a))
        e (* a hh)]
    (if (< m (- e)) (let [dz (+ z hh)] (- (math.sqrt (+ (* qx qx) (* dz dz))) r1))
        (> m e) (let [dz (- z hh)] (- (math.sqrt (+ (* qx qx) (* dz dz))) r2))
        (- (+ (* qx a) (* z b) (* b hh)) r1))))"
 :bounds (fn [o]
           (let [r (max o.radius1 o.radius2)
                 hh (* o.height 0.5)]
             [r r (max (+ hh o.radius1) (+ hh o.radius2))]))}

;; Triangular prism along z: a bound. The equilateral triangle in xy has inradius
;; :radius, its centre at the origin, a flat side at y = -:radius and a corner at
;; y = 2 :radius. The value is the largest of the signed distances to the five planes
;; of the faces: exact inside and where the nearest point lies on a face, but less
;; than the distance near the edges and corners (a bound, never more).

(local cos30 (/ (math.sqrt 3) 2))

{:kind :tri-prism
 :doc "Triangular prism along z: equilateral triangle of inradius :radius (a corner towards +y), full :height."
 :params [{:name :radius :type :positive :default 0.5}
          {:name :height :type :positive :default 1}]
 :class :bound
 :args [{:name :r :type :float} {:name :h :type :float}]
 :pack (fn [o] [o.radius (* o.height 0.5)])
 :glsl-name "sdTriPrism"
 ;; The distance once, in Fennel: src/sdf/translate.fnl writes :glsl and :cpu from it.
 ;; 0.8660254037844386 is cos 30.
 :fennel "(fn [x y z r h]
  (math.max (- (math.abs z) h)
            (- (math.max (+ (* (math.abs x) 0.8660254037844386) (* y 0.5)) (- y)) r)))"
 :bounds (fn [o] [(* o.radius 2 cos30) (* o.radius 2) (* o.height 0.5)])}

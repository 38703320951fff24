;; Cut hollow sphere (a bowl): exact. The spherical shell of :radius with the part above
;; the plane z = :cut removed, walls :thickness either side of the sphere (as the
;; torus's :thickness is its tube radius). The distance to that arc, less the thickness:
;; in the meridian plane q = (|p.xy|, p.z), inside the cone through the rim (w, cut),
;; w = sqrt(r^2 - cut^2), the rim is nearest; elsewhere the circle.
(local {: sqrt} math)

{:kind :cut-hollow-sphere
 :doc "Bowl: a sphere shell of :radius, walls :thickness either side, open above z = :cut."
 :params [{:name :radius :type :positive :default 1}
          {:name :cut :type :number :default 0.5}
          {:name :thickness :type :positive :default 0.05}]
 :check (fn [o]
          (when (not (< (- o.radius) o.cut o.radius))
            (values :cut (.. "must lie strictly between -:radius and :radius ("
                             (- o.radius) " and " o.radius ")"))))
 :class :exact
 :args [{:name :r :type :float} {:name :h :type :float} {:name :w :type :float}
        {:name :t :type :float}]
 :pack (fn [o] [o.radius o.cut (sqrt (- (* o.radius o.radius) (* o.cut o.cut))) o.thickness])
 :glsl-name "sdCutHollowSphere"
 ;; The distance once, in Fennel: src/sdf/translate.fnl writes :glsl and :cpu from it.
 :fennel "(fn [x y z r h w t]
  (let [qx (math.sqrt (+ (* x x) (* y y))) qy z]
    (- (if (< (* h qx) (* w qy))
           (let [dx (- qx w) dy (- qy h)] (math.sqrt (+ (* dx dx) (* dy dy))))
           (math.abs (- (math.sqrt (+ (* qx qx) (* qy qy))) r)))
       t)))"
 :bounds (fn [o]
           (let [e (if (> o.cut 0) o.radius (sqrt (- (* o.radius o.radius) (* o.cut o.cut))))]
             [(+ e o.thickness) (+ e o.thickness) (+ o.radius o.thickness)]))}

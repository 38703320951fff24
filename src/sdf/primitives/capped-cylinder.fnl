;; Capped cylinder: exact. In the plane through the z axis and the point, the shape is a
;; rectangle (:radius by half the :height), so this is the 2D box distance there.
(local {: sqrt : max : min : abs} math)

{:kind :capped-cylinder
 :doc "Cylinder along z of :radius and full :height."
 :params [{:name :radius :type :positive :default 0.5}
          {:name :height :type :positive :default 1}]
 :class :exact
 :args [{:name :r :type :float} {:name :h :type :float}]
 :pack (fn [o] [o.radius (* o.height 0.5)])
 :glsl-name "sdCappedCylinder"
 :glsl "float sdCappedCylinder(vec3 p, float r, float h) {
    vec2 d = abs(vec2(length(p.xy), p.z)) - vec2(r, h);
    return min(max(d.x, d.y), 0.0) + length(max(d, 0.0));
}"
 :cpu (fn [x y z r h]
        (let [dx (- (sqrt (+ (* x x) (* y y))) r)
              dy (- (abs z) h)
              ox (max dx 0) oy (max dy 0)]
          (+ (min (max dx dy) 0) (sqrt (+ (* ox ox) (* oy oy))))))
 :bounds (fn [o] [o.radius o.radius (* o.height 0.5)])}

;; Rhombus (a rounded rhombic slab): exact. The rhombus in the xy plane with
;; half-diagonals :length-a along x and :length-b along y, grown by :radius, extruded to
;; :height along z. Folded into the first quadrant, the nearest point of the edge from
;; (a, 0) to (0, b) has parameter f in [-1, 1] (the ndot form of the projection); the
;; signed 2D distance less the rounding is extruded like a box.
(local {: sqrt : max : min : abs} math)

{:kind :rhombus
 :doc "Rhombic slab: half-diagonals :length-a (x) and :length-b (y), :height (z), edges rounded by :radius."
 :params [{:name :length-a :type :positive :default 0.8}
          {:name :length-b :type :positive :default 0.5}
          {:name :height :type :positive :default 0.3}
          {:name :radius :type :length0 :default 0.05}]
 :class :exact
 :args [{:name :b :type :vec2} {:name :h :type :float} {:name :r :type :float}]
 :pack (fn [o] [o.length-a o.length-b (* o.height 0.5) o.radius])
 :glsl-name "sdRhombus"
 :helpers [:ndot]
 :glsl "float sdRhombus(vec3 p, vec2 b, float h, float r) {
    p = abs(p);
    float f = clamp(ndot(b, b - 2.0 * p.xy) / dot(b, b), -1.0, 1.0);
    float e = length(p.xy - 0.5 * b * vec2(1.0 - f, 1.0 + f))
              * sign(p.x * b.y + p.y * b.x - b.x * b.y) - r;
    vec2 q = vec2(e, p.z - h);
    return min(max(q.x, q.y), 0.0) + length(max(q, 0.0));
}"
 :cpu (fn [x y z ba bb h r]
        (let [x (abs x) y (abs y) z (abs z)
              f (max -1 (min 1 (/ (- (* ba (- ba (* 2 x))) (* bb (- bb (* 2 y))))
                                  (+ (* ba ba) (* bb bb)))))
              ex (- x (* 0.5 ba (- 1 f))) ey (- y (* 0.5 bb (+ 1 f)))
              w (- (+ (* x bb) (* y ba)) (* ba bb))
              sg (if (> w 0) 1 (< w 0) -1 0)
              qx (- (* (sqrt (+ (* ex ex) (* ey ey))) sg) r)
              qy (- z h)
              ox (max qx 0) oy (max qy 0)]
          (+ (min (max qx qy) 0) (sqrt (+ (* ox ox) (* oy oy))))))
 :bounds (fn [o] [(+ o.length-a o.radius) (+ o.length-b o.radius) (* o.height 0.5)])}

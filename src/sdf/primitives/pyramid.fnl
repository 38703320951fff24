;; Pyramid: exact (inside too). A square base of side :base on z = 0, centred on the z
;; axis, apex at z = :height. Worked for a unit base and scaled back. Below the base
;; plane the base square is nearest (every side face leans inwards). Above it the point
;; is folded into one eighth by the square's symmetry and its distance to the one side
;; triangle there is found in that face's frame: q.z along the face normal (times the
;; slant sqrt(m2)), the closest of the face's interior, slanted edge and base edge in
;; the face plane. Inside, the nearer of that face plane and the base plane.
(local {: sqrt : max : min : abs} math)

{:kind :pyramid
 :doc "Square pyramid: base of side :base on z = 0, apex at z = :height."
 :params [{:name :base :type :positive :default 1}
          {:name :height :type :positive :default 1}]
 :class :exact
 :args [{:name :s :type :float} {:name :h :type :float} {:name :m2 :type :float}]
 ;; h is the height for a unit base; m2 = h^2 + 1/4 is the squared slant height.
 :pack (fn [o] (let [h (/ o.height o.base)] [o.base h (+ (* h h) 0.25)]))
 :glsl-name "sdPyramid"
 :glsl "float sdPyramid(vec3 p, float s, float h, float m2) {
    p /= s;
    vec2 b = abs(p.xy);
    if (p.z < 0.0) {
        return s * length(vec3(max(b - 0.5, 0.0), p.z));
    }
    if (b.y > b.x) b = b.yx;
    b -= 0.5;
    vec3 q = vec3(b.y, h * p.z - 0.5 * b.x, h * b.x + 0.5 * p.z);
    float k = max(-q.x, 0.0);
    float t = clamp((q.y - 0.5 * b.y) / (m2 + 0.25), 0.0, 1.0);
    float e = m2 * (q.x + k) * (q.x + k) + q.y * q.y;
    float f = m2 * (q.x + 0.5 * t) * (q.x + 0.5 * t) + (q.y - m2 * t) * (q.y - m2 * t);
    float d2 = min(q.y, -q.x * m2 - q.y * 0.5) > 0.0 ? 0.0 : min(e, f);
    float d = sqrt((d2 + q.z * q.z) / m2);
    return s * (q.z < 0.0 ? max(-d, -p.z) : d);
}"
 :cpu (fn [x y z s h m2]
        (let [x (/ x s) y (/ y s) z (/ z s)
              ax (abs x) ay (abs y)]
          (if (< z 0)
              (let [ox (max (- ax 0.5) 0) oy (max (- ay 0.5) 0)]
                (* s (sqrt (+ (* ox ox) (* oy oy) (* z z)))))
              (let [bx (- (max ax ay) 0.5) by (- (min ax ay) 0.5)
                    qx by
                    qy (- (* h z) (* 0.5 bx))
                    qz (+ (* h bx) (* 0.5 z))
                    k (max (- qx) 0)
                    t (max 0 (min 1 (/ (- qy (* 0.5 by)) (+ m2 0.25))))
                    e (+ (* m2 (+ qx k) (+ qx k)) (* qy qy))
                    f (+ (* m2 (+ qx (* 0.5 t)) (+ qx (* 0.5 t)))
                         (* (- qy (* m2 t)) (- qy (* m2 t))))
                    d2 (if (> (min qy (- (* (- qx) m2) (* qy 0.5))) 0) 0 (min e f))
                    d (sqrt (/ (+ d2 (* qz qz)) m2))]
                (* s (if (< qz 0) (max (- d) (- z)) d))))))
 :bounds (fn [o] (let [e (* o.base 0.5)] [e e o.height]))}

;; Capped cone (a frustum along z): exact. In the plane through the z axis and the point
;; the shape is a trapezoid; the distance is the nearer of the distance to the cap on
;; the point's side and the distance to the slanted side segment, negative when the
;; point is inside both the side and the slab between the caps.
(local {: sqrt : max : min : abs} math)

{:kind :capped-cone
 :doc "Cone frustum along z of full :height, :radius1 at the bottom and :radius2 at the top."
 :params [{:name :height :type :positive :default 1}
          {:name :radius1 :type :length0 :default 0.5}
          {:name :radius2 :type :length0 :default 0.25}]
 :check (fn [o]
          (when (and (<= o.radius1 0) (<= o.radius2 0))
            (values :radius1 "must be positive when :radius2 is 0")))
 :class :exact
 :args [{:name :h :type :float} {:name :r1 :type :float} {:name :r2 :type :float}]
 :pack (fn [o] [(* o.height 0.5) o.radius1 o.radius2])
 :glsl-name "sdCappedCone"
 :helpers [:dot2]
 :glsl "float sdCappedCone(vec3 p, float h, float r1, float r2) {
    vec2 q = vec2(length(p.xy), p.z);
    vec2 k1 = vec2(r2, h);
    vec2 k2 = vec2(r2 - r1, 2.0 * h);
    vec2 ca = vec2(q.x - min(q.x, q.y < 0.0 ? r1 : r2), abs(q.y) - h);
    vec2 cb = q - k1 + k2 * clamp(dot(k1 - q, k2) / dot2(k2), 0.0, 1.0);
    float s = (cb.x < 0.0 && ca.y < 0.0) ? -1.0 : 1.0;
    return s * sqrt(min(dot2(ca), dot2(cb)));
}"
 :cpu (fn [x y z h r1 r2]
        (let [qx (sqrt (+ (* x x) (* y y)))
              qy z
              k2x (- r2 r1) k2y (* 2 h)
              cax (- qx (min qx (if (< qy 0) r1 r2)))
              cay (- (abs qy) h)
              t (max 0 (min 1 (/ (+ (* (- r2 qx) k2x) (* (- h qy) k2y))
                                 (+ (* k2x k2x) (* k2y k2y)))))
              cbx (+ (- qx r2) (* k2x t))
              cby (+ (- qy h) (* k2y t))
              s (if (and (< cbx 0) (< cay 0)) -1 1)]
          (* s (sqrt (min (+ (* cax cax) (* cay cay)) (+ (* cbx cbx) (* cby cby)))))))
 :bounds (fn [o]
           (let [r (max o.radius1 o.radius2)]
             [r r (* o.height 0.5)]))}

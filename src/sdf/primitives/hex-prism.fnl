;; Hexagonal prism along z: exact. The hexagon in xy has its flat sides at y = ±:radius
;; (the apothem) and corners on the x axis. Folded by symmetry so the point faces the
;; top side, the 2D distance is the signed distance to that side's segment; the prism's
;; distance combines it with the distance to the caps like a 2D box.
(local {: sqrt : max : min : abs} math)

(local cos30 (/ (sqrt 3) 2))
(local tan30 (/ 1 (sqrt 3)))

{:kind :hex-prism
 :doc "Hexagonal prism along z: apothem :radius (sides at y = ±radius), full :height."
 :params [{:name :radius :type :positive :default 0.5}
          {:name :height :type :positive :default 1}]
 :class :exact
 ;; r: apothem, e: half the side length, h: half the height.
 :args [{:name :r :type :float} {:name :e :type :float} {:name :h :type :float}]
 :pack (fn [o] [o.radius (* o.radius tan30) (* o.height 0.5)])
 :glsl-name "sdHexPrism"
 :glsl "float sdHexPrism(vec3 p, float r, float e, float h) {
    const vec2 k = vec2(-0.8660254037844386, 0.5);
    p = abs(p);
    p.xy -= 2.0 * min(dot(k, p.xy), 0.0) * k;
    vec2 d = vec2(length(p.xy - vec2(clamp(p.x, -e, e), r)) * sign(p.y - r), p.z - h);
    return min(max(d.x, d.y), 0.0) + length(max(d, 0.0));
}"
 :cpu (fn [x y z r e h]
        (let [ax (abs x) ay (abs y)
              f (* 2 (min (+ (* (- cos30) ax) (* 0.5 ay)) 0))
              px (+ ax (* f cos30))
              py (- ay (* f 0.5))
              sx (- px (max (- e) (min e px)))
              sy (- py r)
              sgn (if (> sy 0) 1 (< sy 0) -1 0)
              dx (* (sqrt (+ (* sx sx) (* sy sy))) sgn)
              dy (- (abs z) h)
              ox (max dx 0) oy (max dy 0)]
          (+ (min (max dx dy) 0) (sqrt (+ (* ox ox) (* oy oy))))))
 :bounds (fn [o] [(/ o.radius cos30) o.radius (* o.height 0.5)])}

;; Box: exact signed distance (negative inside). :size is the full extent, as in the
;; article's scenes; the functions take the half extents.
(local {: sqrt : max : min : abs} math)

{:kind :box
 :doc "Box with full extents :size."
 :params [{:name :size :type :size3 :default [1 1 1]}]
 :class :exact
 :args [{:name :h :type :vec3}]
 :pack (fn [o] (let [[x y z] o.size] [(* x 0.5) (* y 0.5) (* z 0.5)]))
 :glsl-name "sdBox"
 :glsl "float sdBox(vec3 p, vec3 h) {
    vec3 q = abs(p) - h;
    return length(max(q, 0.0)) + min(max(q.x, max(q.y, q.z)), 0.0);
}"
 :cpu (fn [x y z hx hy hz]
        (let [qx (- (abs x) hx) qy (- (abs y) hy) qz (- (abs z) hz)
              ox (max qx 0) oy (max qy 0) oz (max qz 0)]
          (+ (sqrt (+ (* ox ox) (* oy oy) (* oz oz)))
             (min (max qx qy qz) 0))))
 :bounds (fn [o] (let [[x y z] o.size] [(* x 0.5) (* y 0.5) (* z 0.5)]))}

;; Box: exact signed distance (negative inside). :size is the full extent, as in the
;; article's scenes; the functions take the half extents.
(local {: sqrt : max : min : abs} math)

{:kind :box
 :doc "Box with full extents :size."
 :params [{:name :size :type :size3 :default [1 1 1]}]
 :class :exact
 ;; Even in each coordinate and never decreasing as its size grows (see :even in
 ;; src/sdf/primitives.fnl): a centred copy in a repetition is the nearest one.
 :even [true true true]
 :args [{:name :h :type :vec3}]
 :pack (fn [o] (let [[x y z] o.size] [(* x 0.5) (* y 0.5) (* z 0.5)]))
 :glsl-name "sdBox"
 ;; The distance once, in Fennel: src/sdf/translate.fnl writes :glsl and :cpu from it.
 :fennel "(fn [x y z hx hy hz]
  (let [qx (- (math.abs x) hx) qy (- (math.abs y) hy) qz (- (math.abs z) hz)
        ox (math.max qx 0) oy (math.max qy 0) oz (math.max qz 0)]
    (+ (math.sqrt (+ (* ox ox) (* oy oy) (* oz oz)))
       (math.min (math.max qx qy qz) 0))))"
 ;; The exact normal: the distance's gradient. Outside, along the part of p beyond
 ;; the half extents; inside (and on a face), the axis of the nearest face.
 :gradient-glsl "vec3 gradBox(vec3 p, vec3 h) {
    vec3 e = abs(p) - h;
    vec3 s = vec3(p.x < 0.0 ? -1.0 : 1.0, p.y < 0.0 ? -1.0 : 1.0, p.z < 0.0 ? -1.0 : 1.0);
    if (max(e.x, max(e.y, e.z)) > 0.0) {
        vec3 g = max(e, 0.0) * s;
        float len = length(g);
        return len > 0.0 ? g / len : vec3(0.0, 0.0, 1.0);
    }
    if (e.x >= e.y && e.x >= e.z) return vec3(s.x, 0.0, 0.0);
    if (e.y >= e.z) return vec3(0.0, s.y, 0.0);
    return vec3(0.0, 0.0, s.z);
}"
 :gradient (fn [x y z hx hy hz]
             (let [ex (- (abs x) hx) ey (- (abs y) hy) ez (- (abs z) hz)
                   sx (if (< x 0) -1 1) sy (if (< y 0) -1 1) sz (if (< z 0) -1 1)]
               (if (> (max ex ey ez) 0)
                   (let [gx (* (max ex 0) sx) gy (* (max ey 0) sy) gz (* (max ez 0) sz)
                         len (sqrt (+ (* gx gx) (* gy gy) (* gz gz)))]
                     (if (> len 0) (values (/ gx len) (/ gy len) (/ gz len)) (values 0 0 1)))
                   (and (>= ex ey) (>= ex ez)) (values sx 0 0)
                   (>= ey ez) (values 0 sy 0)
                   (values 0 0 sz))))
 :bounds (fn [o] (let [[x y z] o.size] [(* x 0.5) (* y 0.5) (* z 0.5)]))}

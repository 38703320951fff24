;; Box frame (the twelve edges of a box): exact outside. Folded into one octant by
;; symmetry, the frame there is three square bars of width :thickness along the box's
;; edges; each term is the exact distance to one bar (a box, its cross-section folded
;; once more about the bar's centre line), and the least of them is the distance to
;; their union. Inside a bar the value is a bound.
(local {: sqrt : max : min : abs} math)

;; Exact distance to a box given the point's coordinates relative to its faces.
(fn bar [a b c]
  (let [oa (max a 0) ob (max b 0) oc (max c 0)]
    (+ (sqrt (+ (* oa oa) (* ob ob) (* oc oc))) (min (max a b c) 0))))

{:kind :box-frame
 :doc "Frame of the edges of a box with full extents :size, bars :thickness wide."
 :params [{:name :size :type :size3 :default [1 1 1]}
          {:name :thickness :type :positive :default 0.1}]
 :check (fn [o]
          (let [[x y z] o.size
                half (* 0.5 (min x y z))]
            (when (>= o.thickness half)
              (values :thickness (string.format "must be less than half the smallest :size (%g)"
                                                half)))))
 :class :exact
 :args [{:name :b :type :vec3} {:name :e :type :float}]
 :pack (fn [o]
         (let [[x y z] o.size]
           [(* x 0.5) (* y 0.5) (* z 0.5) (* o.thickness 0.5)]))
 :glsl-name "sdBoxFrame"
 :glsl "float sdBoxFrame(vec3 p, vec3 b, float e) {
    p = abs(p) - b;
    vec3 q = abs(p + e) - e;
    float dx = length(max(vec3(p.x, q.y, q.z), 0.0)) + min(max(p.x, max(q.y, q.z)), 0.0);
    float dy = length(max(vec3(q.x, p.y, q.z), 0.0)) + min(max(q.x, max(p.y, q.z)), 0.0);
    float dz = length(max(vec3(q.x, q.y, p.z), 0.0)) + min(max(q.x, max(q.y, p.z)), 0.0);
    return min(dx, min(dy, dz));
}"
 :cpu (fn [x y z bx by bz e]
        (let [px (- (abs x) bx) py (- (abs y) by) pz (- (abs z) bz)
              qx (- (abs (+ px e)) e) qy (- (abs (+ py e)) e) qz (- (abs (+ pz e)) e)]
          (min (bar px qy qz) (bar qx py qz) (bar qx qy pz))))
 :bounds (fn [o] (let [[x y z] o.size] [(* x 0.5) (* y 0.5) (* z 0.5)]))}

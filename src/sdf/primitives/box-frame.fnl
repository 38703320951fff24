;; Box frame (the twelve edges of a box): exact outside. Folded into one octant by
;; symmetry, the frame there is three square bars of width :thickness along the box's
;; edges; each term is the exact distance to one bar (a box, its cross-section folded
;; once more about the bar's centre line), and the least of them is the distance to
;; their union. Inside a bar the value is a bound.
(local {: min} math)

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
 ;; The distance once, in Fennel: src/sdf/translate.fnl writes :glsl and :cpu from it.
 :fennel "(fn [x y z bx by bz e]
  ;; Exact distance to a box given the point's coordinates relative to its faces.
  (fn bar [a b c]
    (let [oa (math.max a 0) ob (math.max b 0) oc (math.max c 0)]
      (+ (math.sqrt (+ (* oa oa) (* ob ob) (* oc oc))) (math.min (math.max a b c) 0))))
  (let [px (- (math.abs x) bx) py (- (math.abs y) by) pz (- (math.abs z) bz)
        qx (- (math.abs (+ px e)) e) qy (- (math.abs (+ py e)) e) qz (- (math.abs (+ pz e)) e)]
    (math.min (bar px qy qz) (bar qx py qz) (bar qx qy pz))))"
 :bounds (fn [o] (let [[x y z] o.size] [(* x 0.5) (* y 0.5) (* z 0.5)]))}

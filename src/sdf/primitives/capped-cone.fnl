;; Capped cone (a frustum along z): exact. In the plane through the z axis and the point
;; the shape is a trapezoid; the distance is the nearer of the distance to the cap on
;; the point's side and the distance to the slanted side segment, negative when the
;; point is inside both the side and the slab between the caps.
(local {: max} math)

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
 ;; The distance once, in Fennel: src/sdf/translate.fnl writes :glsl and :cpu from it.
 :fennel "(fn [x y z h r1 r2]
  (let [qx (math.sqrt (+ (* x x) (* y y)))
        qy z
        k2x (- r2 r1) k2y (* 2 h)
        cax (- qx (math.min qx (if (< qy 0) r1 r2)))
        cay (- (math.abs qy) h)
        t (math.max 0 (math.min 1 (/ (+ (* (- r2 qx) k2x) (* (- h qy) k2y))
                                     (+ (* k2x k2x) (* k2y k2y)))))
        cbx (+ (- qx r2) (* k2x t))
        cby (+ (- qy h) (* k2y t))
        s (if (and (< cbx 0) (< cay 0)) -1 1)]
    (* s (math.sqrt (math.min (+ (* cax cax) (* cay cay)) (+ (* cbx cbx) (* cby cby)))))))"
 :bounds (fn [o]
           (let [r (max o.radius1 o.radius2)]
             [r r (* o.height 0.5)]))}

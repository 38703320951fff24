;; Capsule (a segment with a radius): exact. The distance to the segment from :a to :b,
;; less the radius.
(local {: max : abs} math)

{:kind :capsule
 :doc "Capsule: the segment from :a to :b thickened by :radius."
 :params [{:name :a :type :vec3 :default [0 0 -0.5]}
          {:name :b :type :vec3 :default [0 0 0.5]}
          {:name :radius :type :positive :default 0.25}]
 :class :exact
 :args [{:name :a :type :vec3} {:name :b :type :vec3} {:name :r :type :float}]
 :pack (fn [o] (let [[ax ay az] o.a [bx by bz] o.b] [ax ay az bx by bz o.radius]))
 :glsl-name "sdCapsule"
 ;; The distance once, in Fennel: src/sdf/translate.fnl writes :glsl and :cpu from it.
 :fennel "(fn [x y z ax ay az bx by bz r]
  (let [px (- x ax) py (- y ay) pz (- z az)
        dx (- bx ax) dy (- by ay) dz (- bz az)
        l2 (+ (* dx dx) (* dy dy) (* dz dz))
        h (if (> l2 0) (math.max 0 (math.min 1 (/ (+ (* px dx) (* py dy) (* pz dz)) l2))) 0)
        qx (- px (* dx h)) qy (- py (* dy h)) qz (- pz (* dz h))]
    (- (math.sqrt (+ (* qx qx) (* qy qy) (* qz qz))) r)))"
 :bounds (fn [o]
           (let [[ax ay az] o.a [bx by bz] o.b r o.radius]
             ;; Centred bounds: the largest coordinate of either end, plus the radius.
             [(+ (max (abs ax) (abs bx)) r) (+ (max (abs ay) (abs by)) r)
              (+ (max (abs az) (abs bz)) r)]))}

;; Pyramid: exact (inside too). A square base of side :base on z = 0, centred on the z
;; axis, apex at z = :height. Worked for a unit base and scaled back. Below the base
;; plane the base square is nearest (every side face leans inwards). Above it the point
;; is folded into one eighth by the square's symmetry and its distance to the one side
;; triangle there is found in that face's frame: q.z along the face normal (times the
;; slant sqrt(m2)), the closest of the face's interior, slanted edge and base edge in
;; the face plane. Inside, the nearer of that face plane and the base plane.

{:kind :pyramid
 :doc "Square pyramid: base of side :base on z = 0, apex at z = :height."
 :params [{:name :base :type :positive :default 1}
          {:name :height :type :positive :default 1}]
 :class :exact
 :args [{:name :s :type :float} {:name :h :type :float} {:name :m2 :type :float}]
 ;; h is the height for a unit base; m2 = h^2 + 1/4 is the squared slant height.
 :pack (fn [o] (let [h (/ o.height o.base)] [o.base h (+ (* h h) 0.25)]))
 :glsl-name "sdPyramid"
 ;; The distance once, in Fennel: src/sdf/translate.fnl writes :glsl and :cpu from it.
 :fennel "(fn [x y z s h m2]
  (let [x (/ x s) y (/ y s) z (/ z s)
        ax (math.abs x) ay (math.abs y)]
    (if (< z 0)
        (let [ox (math.max (- ax 0.5) 0) oy (math.max (- ay 0.5) 0)]
          (* s (math.sqrt (+ (* ox ox) (* oy oy) (* z z)))))
        (let [bx (- (math.max ax ay) 0.5) by (- (math.min ax ay) 0.5)
              qx by
              qy (- (* h z) (* 0.5 bx))
              qz (+ (* h bx) (* 0.5 z))
              k (math.max (- qx) 0)
              t (math.max 0 (math.min 1 (/ (- qy (* 0.5 by)) (+ m2 0.25))))
              e (+ (* m2 (+ qx k) (+ qx k)) (* qy qy))
              f (+ (* m2 (+ qx (* 0.5 t)) (+ qx (* 0.5 t)))
                   (* (- qy (* m2 t)) (- qy (* m2 t))))
              d2 (if (> (math.min qy (- (* (- qx) m2) (* qy 0.5))) 0) 0 (math.min e f))
              d (math.sqrt (/ (+ d2 (* qz qz)) m2))]
          (* s (if (< qz 0) (math.max (- d) (- z)) d))))))"
 :bounds (fn [o] (let [e (* o.base 0.5)] [e e o.height]))}

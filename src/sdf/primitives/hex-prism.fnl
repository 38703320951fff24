;; Hexagonal prism along z: exact. The hexagon in xy has its flat sides at y = ±:radius
;; (the apothem) and corners on the x axis. Folded by symmetry so the point faces the
;; top side, the 2D distance is the signed distance to that side's segment; the prism's
;; distance combines it with the distance to the caps like a 2D box.
(local {: sqrt} math)

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
 ;; The distance once, in Fennel: src/sdf/translate.fnl writes :glsl and :cpu from it.
 ;; 0.8660254037844386 is cos 30.
 :fennel "(fn [x y z r e h]
  (let [ax (math.abs x) ay (math.abs y)
        f (* 2 (math.min (+ (* -0.8660254037844386 ax) (* 0.5 ay)) 0))
        px (+ ax (* f 0.8660254037844386))
        py (- ay (* f 0.5))
        sx (- px (math.max (- e) (math.min e px)))
        sy (- py r)
        sgn (if (> sy 0) 1 (< sy 0) -1 0)
        dx (* (math.sqrt (+ (* sx sx) (* sy sy))) sgn)
        dy (- (math.abs z) h)
        ox (math.max dx 0) oy (math.max dy 0)]
    (+ (math.min (math.max dx dy) 0) (math.sqrt (+ (* ox ox) (* oy oy))))))"
 :bounds (fn [o] [(/ o.radius cos30) o.radius (* o.height 0.5)])}

;; Vesica (a lens or lemon): exact. The 2D vesica, the overlap of two discs of radius r
;; whose centres lie d either side of the axis, revolved around the z axis: tips at
;; z = +-:length/2, widest (:width) at z = 0. Its distance in the meridian plane
;; (|p.xy|, |p.z|) is the exact distance: the tip (0, b) when the point is past the arc's
;; normal at the tip, else the distance to the arc's circle centred at (-d, 0).
;; With b = length/2 and half width c = width/2: d = (b^2 - c^2) / 2c and r = d + c.

{:kind :vesica
 :doc "Lens shape revolved around z: tips :length apart along z, :width across at z = 0."
 :params [{:name :length :type :positive :default 2}
          {:name :width :type :positive :default 1}]
 :check (fn [o]
          (when (> o.width o.length)
            (values :width (.. "must be at most :length (" o.length ")"))))
 :class :exact
 :args [{:name :r :type :float} {:name :d :type :float} {:name :b :type :float}]
 :pack (fn [o]
         (let [b (* o.length 0.5) c (* o.width 0.5)
               d (/ (- (* b b) (* c c)) (* 2 c))]
           [(+ d c) d b]))
 :glsl-name "sdVesica"
 ;; The distance once, in Fennel: src/sdf/translate.fnl writes :glsl and :cpu from it.
 :fennel "(fn [x y z r d b]
  (let [qx (math.sqrt (+ (* x x) (* y y))) qy (math.abs z)]
    (if (> (* (- qy b) d) (* qx b))
        (let [dy (- qy b)] (math.sqrt (+ (* qx qx) (* dy dy))))
        (let [dx (+ qx d)] (- (math.sqrt (+ (* dx dx) (* qy qy))) r)))))"
 :bounds (fn [o] (let [c (* o.width 0.5)] [c c (* o.length 0.5)]))}

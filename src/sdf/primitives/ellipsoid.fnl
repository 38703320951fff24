;; Ellipsoid: a bound (nearly exact outside). The nearest point of the surface to p is
;; x(t) = r^2 p / (t + r^2) for the t >= 0 where |x(t) / r| = 1, that is where
;; |a(t)| = 1 for a(t) = r p / (t + r^2). 1 / |a(t)| is a power mean of lines in t, so
;; it is concave, and Newton's method on 1 / |a(t)| - 1 from t = 0 climbs towards that
;; root without passing it; four steps are taken (the first in closed form). Whatever t
;; is reached, x(t) is scaled onto the surface and the distance from p to the tangent
;; plane there is returned: the ellipsoid lies behind every tangent plane, so this
;; never exceeds the distance, and it is the distance once t has converged (within 1%
;; for axis ratios up to 20:1). Inside, k0 (k0 - 1) / k1 (k0 = |p/r|, k1 = |p/r^2|, the
;; tangent plane at the radial projection) can overshoot (-max radius at the centre),
;; so it is capped by min(r) (k0 - 1), which is 1-Lipschitz and zero on the surface.
(local {: min} math)

{:kind :ellipsoid
 :doc "Ellipsoid with semi-axes :radii along x, y and z."
 :params [{:name :radii :type :size3 :default [1 0.75 0.5]}]
 :class :bound
 ;; The same at -v as at v in each coordinate (see :symmetric in src/sdf/primitives.fnl).
 :symmetric [true true true]
 :args [{:name :r :type :vec3} {:name :rmin :type :float}]
 :pack (fn [o] (let [[x y z] o.radii] [x y z (min x y z)]))
 :glsl-name "sdEllipsoid"
 ;; The distance once, in Fennel: src/sdf/translate.fnl writes :glsl and :cpu from it.
 :fennel "(fn [x y z rx ry rz rmin]
  (let [ux (/ x rx) uy (/ y ry) uz (/ z rz)
        vx (/ ux rx) vy (/ uy ry) vz (/ uz rz)
        k0 (math.sqrt (+ (* ux ux) (* uy uy) (* uz uz)))
        k1 (math.sqrt (+ (* vx vx) (* vy vy) (* vz vz)))
        rx2 (* rx rx) ry2 (* ry ry) rz2 (* rz rz)]
    (if (< k0 1)
        (math.max (if (> k1 0) (/ (* k0 (- k0 1)) k1) (- rmin)) (* rmin (- k0 1)))
        (do
          (var t (/ (* (- k0 1) k0 k0) (* k1 k1)))
          (for [_ 1 3]
            (let [wx (/ 1 (+ t rx2)) wy (/ 1 (+ t ry2)) wz (/ 1 (+ t rz2))
                  ax (* rx x wx) ay (* ry y wy) az (* rz z wz)
                  s2 (+ (* ax ax) (* ay ay) (* az az))]
              (set t (+ t (/ (* (- (math.sqrt s2) 1) s2)
                             (+ (* ax ax wx) (* ay ay wy) (* az az wz)))))))
          (let [px (/ (* rx2 x) (+ t rx2)) py (/ (* ry2 y) (+ t ry2)) pz (/ (* rz2 z) (+ t rz2))
                k (math.sqrt (+ (* (/ px rx) (/ px rx)) (* (/ py ry) (/ py ry)) (* (/ pz rz) (/ pz rz))))
                px (/ px k) py (/ py k) pz (/ pz k)
                nx (/ px rx2) ny (/ py ry2) nz (/ pz rz2)
                nl (math.sqrt (+ (* nx nx) (* ny ny) (* nz nz)))]
            (/ (+ (* (- x px) nx) (* (- y py) ny) (* (- z pz) nz)) nl))))))"
 :bounds (fn [o] (let [[x y z] o.radii] [x y z]))}

;; The twist operation (point): its descriptor, as src/sdf/operations.fnl lists
;; the fields.

(local {: sqrt : abs : max : sin : cos} math)
(local {: rad : bound-class} (require :src.sdf.operation-kit))

(fn shear-factor [k rho]
  ;; Largest singular value of I + v e^T with |v| = k rho (v orthogonal to e): the
  ;; Lipschitz factor of twisting or bending a point at distance rho from the axis.
  (let [v (* (abs k) rho)]
    (* 0.5 (+ v (sqrt (+ (* v v) 4))))))

{:kind :twist :role :point
 :class-doc "bound, Lipschitz from the child's radius"
 :doc "Twists its child about the z axis by :angle degrees per unit of height (Lipschitz factor grows with the child's radius)."
 :params [{:name :angle :type :degrees :min -3600 :max 3600 :default 45}]
 :children [1 1]
 ;; k in radians per unit, and rho0 the child's radius about z (from its bounds).
 :args [{:name :k :type :float} {:name :rho0 :type :float}]
 :pack (fn [o child] (let [[hx hy] child.bounds] [(rad o.angle) (sqrt (+ (* hx hx) (* hy hy)))]))
 :glsl-name "opTwist"
 :glsl "vec3 opTwist(vec3 p, float k, float rho0) {
    float c = cos(k * p.z);
    float s = sin(k * p.z);
    return vec3(c * p.x + s * p.y, -s * p.x + c * p.y, p.z);
}"
 :cpu (fn [x y z k]
        (let [c (cos (* k z)) s (sin (* k z))]
          (values (+ (* c x) (* s y)) (- (* c y) (* s x)) z)))
 ;; The twist stretches space by at most the shear factor at the largest radius a
 ;; straight path from p to the child passes: max(radius of p, rho0). Dividing by
 ;; it at each point keeps the distance a bound everywhere, near or far.
 :post {:glsl-name "opTwistDistance"
        :glsl "float opTwistDistance(float d, vec3 p, float k, float rho0) {
    float v = abs(k) * max(length(p.xy), rho0);
    return d / (0.5 * (v + sqrt(v * v + 4.0)));
}"
        :cpu (fn [d x y _ k rho0]
               (let [v (* (abs k) (max (sqrt (+ (* x x) (* y y))) rho0))]
                 (/ d (* 0.5 (+ v (sqrt (+ (* v v) 4)))))))}
 :needs-bounds "x and y"
 :corrects? true
 :lipschitz-of (fn [o children]
                 (let [[hx hy] (. children 1 :bounds)]
                   (shear-factor (rad o.angle) (sqrt (+ (* hx hx) (* hy hy))))))
 :class-of bound-class
 :bounds-of (fn [_ children]
              (let [[hx hy hz] (. children 1 :bounds)
                    r (sqrt (+ (* hx hx) (* hy hy)))]
                [r r hz]))
 ;; Nodes the tests check it on (test/operations_spec.fnl): its promises on each,
 ;; sampled within :extent (half extents about the origin).
 :examples [{:name "twist" :extent [1.5 1.5 2.5]
             :node "{:kind :twist :angle 30 :children [{:kind :box :size [1 1 3]}]}"}]}

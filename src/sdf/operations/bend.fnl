;; The bend operation (point): its descriptor, as src/sdf/operations.fnl lists
;; the fields.

(local {: sqrt : abs : max : sin : cos} math)
(local {: rad : bound-class} (require :src.sdf.operation-kit))

{:kind :bend :role :point
 :class-doc "bound, Lipschitz from the child's size"
 :doc "Bends its child in the xz plane: :angle degrees of turn per unit along x (Lipschitz factor grows with the child's size)."
 :params [{:name :angle :type :degrees :min -3600 :max 3600 :default 20}]
 :children [1 1]
 :args [{:name :k :type :float} {:name :rho0 :type :float}]
 :pack (fn [o child] (let [[hx _ hz] child.bounds] [(rad o.angle) (sqrt (+ (* hx hx) (* hz hz)))]))
 :glsl-name "opBend"
 :glsl "vec3 opBend(vec3 p, float k, float rho0) {
    float c = cos(k * p.x);
    float s = sin(k * p.x);
    return vec3(c * p.x - s * p.z, p.y, s * p.x + c * p.z);
}"
 :cpu (fn [x y z k]
        (let [c (cos (* k x)) s (sin (* k x))]
          (values (- (* c x) (* s z)) y (+ (* s x) (* c z)))))
 ;; The bent point is R(k x) (x, z): its derivative along x gains k times the
 ;; rotated (x, z), which is not orthogonal to x, so the factor is 1 + k rho (rho
 ;; as for the twist: the largest radius about y on the way to the child).
 :post {:glsl-name "opBendDistance"
        :glsl "float opBendDistance(float d, vec3 p, float k, float rho0) {
    return d / (1.0 + abs(k) * max(length(p.xz), rho0));
}"
        :cpu (fn [d x _ z k rho0]
               (/ d (+ 1 (* (abs k) (max (sqrt (+ (* x x) (* z z))) rho0)))))}
 :needs-bounds "x and z"
 :corrects? true
 :lipschitz-of (fn [o children]
                 (let [[hx _ hz] (. children 1 :bounds)]
                   (+ 1 (* (abs (rad o.angle)) (sqrt (+ (* hx hx) (* hz hz)))))))
 :class-of bound-class
 :bounds-of (fn [_ children]
              (let [[hx hy hz] (. children 1 :bounds)
                    r (sqrt (+ (* hx hx) (* hz hz)))]
                [r hy r]))
 ;; Nodes the tests check it on (test/operations_spec.fnl): its promises on each,
 ;; sampled within :extent (half extents about the origin).
 :examples [{:name "bend" :extent [2.5 1.5 2]
             :node "{:kind :bend :angle 20 :children [{:kind :box :size [3 1 0.5]}]}"}]}

;; The stairs-union operation (combine): its descriptor, as src/sdf/operations.fnl lists
;; the fields.

(local {: min : max} math)
(local {: bound-class : merge-bounds : grow-bounds} (require :src.sdf.operation-kit))

{:kind :stairs-union :role :combine
 :class-doc "bound"
 :doc "Union with :steps stair steps over :radius where the children meet."
 :params [{:name :radius :type :positive :default 0.25}
          {:name :steps :type :count :min 1 :max 16 :default 3}]
 :children [2]
 :args [{:name :r :type :float} {:name :n :type :float}]
 :pack (fn [o] [o.radius o.steps])
 :glsl-name "opStairsUnion"
 ;; The corner between the two surfaces filled with n square steps: the union of
 ;; the quarter planes a < (i + 1) s, b < (n - i) s for i = 0 .. n - 1, s = r / n;
 ;; each is max(a - ai, b - bi), a bound, like the union itself.
 :glsl "float opStairsUnion(float a, float b, float r, float n) {
    float s = r / n;
    float d = min(a, b);
    for (float i = 0.0; i < n; i += 1.0) {
        d = min(d, max(a - (i + 1.0) * s, b - (n - i) * s));
    }
    return d;
}
float wStairsUnion(float a, float b, float r, float n) {
    return a <= b ? 1.0 : 0.0;
}"
 :cpu (fn [a b r n]
        (let [s (/ r n)]
          (var d (min a b))
          (for [i 0 (- n 1)]
            (set d (min d (max (- a (* (+ i 1) s)) (- b (* (- n i) s))))))
          d))
 :cpu-weight (fn [a b] (if (<= a b) 1 0))
 :class-of bound-class
 :bounds-of (fn [o children] (grow-bounds (merge-bounds o children) o.radius))
 ;; Nodes the tests check it on (test/operations_spec.fnl): its promises on each,
 ;; sampled within :extent (half extents about the origin).
 :examples [{:name "stairs-union" :extent [2 2 3]
             :node "{:kind :stairs-union :radius 0.6 :steps 3 :children [{:kind :box :size [3 3 1]} {:kind :box :size [1 1 3] :pos [0 0 1]}]}"}]}

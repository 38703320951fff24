;; The mirror operation (point): its descriptor, as src/sdf/operations.fnl lists
;; the fields.

(local {: sqrt : abs : min : max} math)
(local {: bound-class} (require :src.sdf.operation-kit))

(fn mirror-cpu [x y z nx ny nz]
  (let [k (* 2 (min (+ (* x nx) (* y ny) (* z nz)) 0))]
    (values (- x (* k nx)) (- y (* k ny)) (- z (* k nz)))))

;; A mirror across a plane of the axes (a normal of +-1 along one axis, 0 on the
;; others): the coordinate along it made +-|v|, the same floats as the general form's
;; p - 2 min(p.n, 0) n, in 1 operation instead of 7 (colonnade's two rows of
;; columns: 4% of a frame).
(local mirror-axes
  (collect [i axis (ipairs ["x" "y" "z"])]
    i (let [name (.. "opMirror" (axis:upper))
            parts (icollect [_ a (ipairs ["x" "y" "z"])]
                    (if (= a axis) (.. "n." a " * abs(p." a ")") (.. "p." a)))]
        {:glsl-name name
         :glsl (.. "vec3 " name "(vec3 p, vec3 n) {\n    return vec3("
                   (table.concat parts ", ") ");\n}")
         :cpu mirror-cpu})))

(fn mirror-axis [o]
  ;; 1, 2 or 3 when the normal is +-1 along that axis and 0 along the others.
  (accumulate [found nil i v (ipairs o.normal)]
    (if (= 1 (abs v)) (when (= 2 (accumulate [zeros 0 _ w (ipairs o.normal)]
                                   (if (= 0 w) (+ zeros 1) zeros)))
                        i)
        found)))

{:kind :mirror :role :point
 :class-doc "bound (exact when the child is on the normal's side)"
 :doc "Mirrors its child across the plane through the origin with :normal (the child's half on the normal's side is kept)."
 :params [{:name :normal :type :direction :default [1 0 0]}]
 :children [1 1]
 :args [{:name :n :type :vec3}] :pack (fn [o] o.normal)
 :glsl-name "opMirror"
 :glsl "vec3 opMirror(vec3 p, vec3 n) {
    return p - 2.0 * min(dot(p, n), 0.0) * n;
}"
 :cpu mirror-cpu
 :variant-of (fn [o] (. mirror-axes (mirror-axis o)))
 ;; A normal across the axis leaves that coordinate alone.
 :keeps-even (fn [o axis] (= 0 (. o.normal axis)))
 ;; Mirrored across that axis itself, symmetric whatever the child.
 :symmetric-of (fn [o children axis]
                 (or (= 1 (abs (. o.normal axis)))
                     (and (= 0 (. o.normal axis)) (= true (?. children 1 :symmetric axis)))))
 ;; The box of the child's box and its mirror image: holds the kept half and its
 ;; image (tighter than the bounds' circle about the normal).
 :box-of (fn [o [child]]
           (let [[nx ny nz] o.normal
                 lo [math.huge math.huge math.huge]
                 hi [(- math.huge) (- math.huge) (- math.huge)]]
             (each [_ x (ipairs [(. child.lo 1) (. child.hi 1)])]
               (each [_ y (ipairs [(. child.lo 2) (. child.hi 2)])]
                 (each [_ z (ipairs [(. child.lo 3) (. child.hi 3)])]
                   (let [k (* 2 (+ (* x nx) (* y ny) (* z nz)))]
                     (each [_ q (ipairs [[x y z] [(- x (* k nx)) (- y (* k ny)) (- z (* k nz))]])]
                       (for [i 1 3]
                         (tset lo i (min (. lo i) (. q i)))
                         (tset hi i (max (. hi i) (. q i)))))))))
             {: lo : hi}))
 ;; Exact when the child lies on the normal's side; otherwise still a bound.
 :class-of bound-class
 :bounds-of (fn [o children]
              (let [b (. children 1 :bounds)]
                (when b (let [r (sqrt (+ (* (. b 1) (. b 1)) (* (. b 2) (. b 2))
                                         (* (. b 3) (. b 3))))]
                          [r r r]))))
 ;; Nodes the tests check it on (test/operations_spec.fnl): its promises on each,
 ;; sampled within :extent (half extents about the origin).
 :examples [{:name "mirror" :extent [4 2 2]
             :node "{:kind :mirror :normal [1 0 0] :children [{:kind :sphere :radius 1 :pos [2 0 0]}]}"}]}

;; The rotate operation (point): its descriptor, as src/sdf/operations.fnl lists
;; the fields.

(local {: abs : sin : cos} math)
(local {: rad : first-class} (require :src.sdf.operation-kit))

(fn rotation-rows [o]
  "Rows of the matrix that maps a world point into the child's frame (the inverse,
i.e. the transpose, of the rotation): [r1x r1y r1z r2x ... r3z]."
  (let [m (if o.axis
              ;; Rodrigues' formula for a rotation by :angle about the unit :axis.
              (let [[x y z] o.axis
                    a (rad o.angle) c (cos a) s (sin a) t (- 1 c)]
                [[(+ (* t x x) c) (- (* t x y) (* s z)) (+ (* t x z) (* s y))]
                 [(+ (* t x y) (* s z)) (+ (* t y y) c) (- (* t y z) (* s x))]
                 [(- (* t x z) (* s y)) (+ (* t y z) (* s x)) (+ (* t z z) c)]])
              ;; Degrees about x, then y, then z: R = Rz Ry Rx.
              (let [[ax ay az] o.angles
                    cx (cos (rad ax)) sx (sin (rad ax))
                    cy (cos (rad ay)) sy (sin (rad ay))
                    cz (cos (rad az)) sz (sin (rad az))]
                [[(* cz cy) (- (* cz sy sx) (* sz cx)) (+ (* cz sy cx) (* sz sx))]
                 [(* sz cy) (+ (* sz sy sx) (* cz cx)) (- (* sz sy cx) (* cz sx))]
                 [(- sy) (* cy sx) (* cy cx)]]))
        [[a b c] [d e f] [g h i]] m]
    ;; Transpose: the child sees R^T p.
    [a d g b e h c f i]))

(fn rotate-bounds [o children]
  (let [b (. children 1 :bounds)]
    (when b
      (let [[hx hy hz] b
            [a b2 c d e f g h i] (rotation-rows o)]
        ;; The box of the rotated box: |R| h, with R = the transpose of the rows.
        [(+ (* (abs a) hx) (* (abs d) hy) (* (abs g) hz))
         (+ (* (abs b2) hx) (* (abs e) hy) (* (abs h) hz))
         (+ (* (abs c) hx) (* (abs f) hy) (* (abs i) hz))]))))

(fn symmetric-rotation? [o axis]
  ;; A rotation that maps the axis onto itself commutes with the reflection along it.
  (let [rows (rotation-rows o)]
    (accumulate [ok? true _ i (ipairs [1 2 3])]
      (and ok? (or (= i axis)
                   (and (= 0 (. rows (+ (* 3 (- i 1)) axis)))
                        (= 0 (. rows (+ (* 3 (- axis 1)) i)))))))))

(fn axis-permutation [o]
  ;; "ZYX" and the like when the rotation only permutes the axes (with signs): each
  ;; row of the child's matrix has one entry of magnitude 1 (within 1e-12; cos 90
  ;; degrees is 6e-17 in double) and the rest 0. The letter is the column of row i's
  ;; entry: the coordinate the child's i-th one is taken from.
  (let [rows (rotation-rows o)
        letters []]
    (for [i 1 3]
      (var found nil)
      (var ok? true)
      (for [j 1 3]
        (let [v (abs (. rows (+ (* 3 (- i 1)) j)))]
          (if (< (abs (- v 1)) 1e-12) (if found (set ok? false) (set found j))
              (>= v 1e-12) (set ok? false))))
      (table.insert letters (when (and ok? found) (. ["X" "Y" "Z"] found))))
    (when (= 3 (length letters)) (table.concat letters))))

(local rotate-permutations {})

(fn rotate-permutation [perm]
  ;; The rotation by swizzles: each coordinate of the child's point is one of the
  ;; point's times its row's entry there (+-1; the 6e-17 beside it left out: under
  ;; float32's rounding of the product). 3 multiplications instead of 3 dot products
  ;; (colonnade's arches, a quarter turn about y: 3% of a frame). The CPU form keeps
  ;; the whole matrix.
  (when (not (. rotate-permutations perm))
    (let [name (.. "opRotate" perm)
          terms (fcollect [i 1 3]
                  (let [c (: (perm:sub i i) :lower)]
                    (.. "r" (- i 1) "." c " * p." c)))]
      (tset rotate-permutations perm
            {:glsl-name name
             :glsl (.. "vec3 " name "(vec3 p, vec3 r0, vec3 r1, vec3 r2) {\n"
                       "    return vec3(" (table.concat terms ", ") ");\n}")
             :cpu (fn [x y z a b c d e f g h i]
                    (values (+ (* a x) (* b y) (* c z)) (+ (* d x) (* e y) (* f z))
                            (+ (* g x) (* h y) (* i z))))})))
  (. rotate-permutations perm))

{:kind :rotate :role :point
 :class-doc "keeps"
 :doc "Rotates its child: :angles [x y z] in degrees (about x, then y, then z), or :axis and :angle."
 :params [{:name :angles :type :vec3 :default [0 0 0]}
          {:name :axis :type :direction :optional? true}
          {:name :angle :type :degrees :min -3600 :max 3600 :default 0}]
 :children [1 1]
 :args [{:name :r0 :type :vec3} {:name :r1 :type :vec3} {:name :r2 :type :vec3}]
 :pack rotation-rows
 :glsl-name "opRotate"
 :glsl "vec3 opRotate(vec3 p, vec3 r0, vec3 r1, vec3 r2) {
    return vec3(dot(r0, p), dot(r1, p), dot(r2, p));
}"
 :cpu (fn [x y z a b c d e f g h i]
        (values (+ (* a x) (* b y) (* c z)) (+ (* d x) (* e y) (* f z))
                (+ (* g x) (* h y) (* i z))))
 :variant-of (fn [o] (let [perm (axis-permutation o)] (when perm (rotate-permutation perm))))
 :keeps-symmetric symmetric-rotation?
 :class-of first-class
 :bounds-of rotate-bounds
 ;; Nodes the tests check it on (test/operations_spec.fnl): its promises on each,
 ;; sampled within :extent (half extents about the origin).
 :examples [{:name "rotate-angles" :extent [2 2 2]
             :node "{:kind :rotate :angles [0 0 90] :children [{:kind :box :size [2 1 1]}]}"}
            {:name "rotate-axis" :extent [2 2 2]
             :node "{:kind :rotate :axis [0 0 2] :angle 90 :children [{:kind :box :size [2 1 1]}]}"}]}

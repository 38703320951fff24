;; Tetrahedron: a bound. Regular, centroid at the origin, one vertex straight up at
;; z = :size, the opposite face flat at z = -size/3, one lower vertex towards +y (so a
;; face looks towards -y). The largest of the four face-plane distances: exact inside
;; and over the faces, less than the distance beyond edges and vertices. Side normals
;; have z = 1/3 and horizontal length 2 sqrt(2)/3; the two towards +-x are folded into
;; one with |x|. The inradius is size/3.

{:kind :tetrahedron
 :doc "Regular tetrahedron, vertices :size from the centre, one vertex up, a face down."
 :params [{:name :size :type :positive :default 1}]
 :class :bound
 :args [{:name :r :type :float}]
 :pack (fn [o] [(/ o.size 3)])
 :glsl-name "sdTetrahedron"
 ;; The distance once, in Fennel: src/sdf/translate.fnl writes :glsl and :cpu from it.
 :fennel "(fn [x y z r]
  (let [z3 (* z 0.33333333333333333)]
    (- (math.max (- z) (- z3 (* 0.94280904158206347 y))
                 (+ z3 (* 0.81649658092772603 (math.abs x)) (* 0.47140452079103173 y)))
       r)))"
 :bounds (fn [o] (let [s o.size] [(* s 0.81649658092772603) (* s 0.94280904158206347) s]))}

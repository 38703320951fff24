;; The CPU reference's surface normals: finite differences of the scene's or the
;; nearest object's distance (plan.normals: one-sided, central or tetrahedron), or
;; the object's exact gradient (normal-exact.glsl, normal-crease.glsl).

(local {: safe-normalize} (require :src.reference.vec))

(fn normals [ctx parts]
  "The normals of a tracer's settings `ctx` (src/reference/settings.fnl) over
`parts` (its distance field and hit tests): a table of
  :differences  (fn [map x y z h]) -> nx ny nz, plan.normals differences of `map`
                with step h
  :normal       (fn [x y z]) -> nx ny nz (plan.normals differences of the nearest
                object's distance, or with :normals-of :scene the whole scene's)
  :crease?      (fn [x y z]) -> whether two objects come within twice normal-delta"
  (let [{: plan : normal-method : tape-gradient : tally} ctx
        {: map : map-color : near-count : others-map : object-map : normal-delta} parts]
    (fn crease? [x y z]
      ;; Two objects meet within the normal's finite-difference reach of the point:
      ;; a whole-scene normal there points between their surfaces.
      (let [reach (* 2 (normal-delta x y z))]
        (>= (near-count x y z reach) 2)))

    (fn differences [map x y z h]
      (tally :normal (if (= normal-method :central) 6 4))
      (case normal-method
          :one-sided (let [d (map x y z)]
                       (safe-normalize (- d (map (- x h) y z))
                                       (- d (map x (- y h) z))
                                       (- d (map x y (- z h)))))
          :central (safe-normalize (- (map (+ x h) y z) (map (- x h) y z))
                                   (- (map x (+ y h) z) (map x (- y h) z))
                                   (- (map x y (+ z h)) (map x y (- z h))))
          :tetrahedron (let [a (map (+ x h) (- y h) (- z h))   ; k.xyy
                             b (map (- x h) (- y h) (+ z h))   ; k.yyx
                             c (map (- x h) (+ y h) (- z h))   ; k.yxy
                             e (map (+ x h) (+ y h) (+ z h))]  ; k.xxx
                         (safe-normalize (+ a (- b) (- c) e)
                                         (+ (- a) (- b) c e)
                                         (+ (- a) b (- c) e)))))

    (fn normal [x y z]
      ;; The whole scene's differences with :normals-of :scene (or when no object is
      ;; near); else the nearest object's exact gradient when it has one (a field's
      ;; object or a leaf's: normal-exact.glsl), or its own differences (mapObject),
      ;; taken where another object comes within 2h at the point pushed out of its
      ;; reach (normal-crease.glsl).
      (let [h (normal-delta x y z)
            (_ i) (map-color x y z)]
        (if (and plan.exact-normals? (not i))
            (values 0 0 1)
            (or (= plan.normals-of :scene) (not i))
            (differences map x y z h)
            (. tape-gradient i)
            ((. tape-gradient i) x y z)
            (let [others (others-map i)
                  other (others x y z)]
              (tally :normal (if (< other (* 2 h)) 7 1))
              (if (< other (* 2 h))
                  (let [(ax ay az) (safe-normalize (- (others (+ x h) y z) (others (- x h) y z))
                                                   (- (others x (+ y h) z) (others x (- y h) z))
                                                   (- (others x y (+ z h)) (others x y (- z h))))
                        push (- (* 2 h) other)]
                    (differences (object-map i) (+ x (* ax push)) (+ y (* ay push)) (+ z (* az push)) h))
                  (differences (object-map i) x y z h))))))

    {: differences : normal : crease?}))

{: normals}

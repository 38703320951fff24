;; The CPU reference's hit tests (shaders/pipeline/hit/): when a step is short enough
;; to be a hit, the start limit of secondary rays, and the normals' step, all scaled
;; by the distance from the camera.

(local sqrt math.sqrt)

(fn tests [ctx]
  "The hit tests of a tracer's settings `ctx` (src/reference/settings.fnl): a table of
  :threshold             (fn [dist]) -> a step shorter than this is a hit, dist the
                         distance from the camera along the ray's path
  :start-limit           (fn [d]) -> the nearest a secondary ray may come to count a
                         hit, given the distance d at its start
  :distance-from-camera  (fn [x y z]) -> distance
  :normal-delta          (fn [x y z]) -> the finite-difference step (and, twice it,
                         the offset of secondary rays)"
  (let [{: hit-test : eps : pixel-angle : draw} ctx
        [cx cy cz] ctx.cam]
    (fn threshold [dist]
      (case hit-test
        :fixed eps
        :relative (* eps dist)
        :pixel (* eps dist pixel-angle)))

    (fn start-limit [d]
      ;; startLimit: half of d, except in the article's fixed test or from inside a
      ;; solid.
      (if (or (= hit-test :fixed) (<= d 0)) draw (* 0.5 d)))

    (fn distance-from-camera [x y z]
      (let [ex (- x cx) ey (- y cy) ez (- z cz)]
        (sqrt (+ (* ex ex) (* ey ey) (* ez ez)))))

    (fn normal-delta [x y z]
      (let [dist (distance-from-camera x y z)]
        (math.max (threshold dist) (* 0.000001 (+ 1 dist)))))

    {: threshold : start-limit : distance-from-camera : normal-delta}))

{: tests}

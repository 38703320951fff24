;; tier: fast
;; The article's CPU program as `make bench` runs it (test/bench/article.fnl): its scene
;; is the seed's. Its distance estimator agrees with our CPU evaluator of
;; scenes/seed.fnl at points outside every object (the article's box distance is zero
;; inside a box, ours negative), and a ray down the middle of the view meets the
;; same surface.
(local article (require :test.bench.article))
(local load (require :src.scene.load))
(local plan-mod (require :src.render.plan))
(local probe (require :src.app.probe))

(describe "the article's program in the benchmark"
  (fn []
    (let [scene (assert (load.load-file "scenes/seed.fnl"))
          plan (assert (plan-mod.scene->plan scene {:view :glow :probe? true}))]
      (it "measures the seed scene's distances and colours"
        (fn []
          (let [points [[20 50 20] [0 0 20] [-10 10 1] [6 -5 12] [5 5 0.5] [-2.7 2.5 6]
                        [30 -30 3] [0 -20 25]]
                want (probe.cpu-values scene plan points)]
            (each [i p (ipairs points)]
              (let [(d color) (article.estimate p)
                    w (. want i)]
                ;; 1e-9: the same formulas in doubles, summed in another order.
                (assert.is_true (< (math.abs (- d w.distance)) 1e-9)
                                (string.format "point %d: %.12g against %.12g" i d w.distance))
                (assert.are.same w.color color (.. "point " i)))))))
      (it "marches a ray onto the surface the scene has there"
        (fn []
          (let [(t _ steps) (article.march [20 50 20] [0 0 -1])
                ;; Straight down from the camera: the floor at z = 0 (nothing in between).
                ]
            (assert.is_true (< (math.abs (- t 20)) 1e-3) (tostring t))
            (assert.is_true (> steps 1))))))))

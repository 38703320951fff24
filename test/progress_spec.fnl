;; Progressive rendering's schedule (src/app/progress.fnl): how a heavy frame is split into
;; bands drawn one per frame, with frame times fed in (no clock, no GPU).
(local progress (require :src.app.progress))

(fn draw-frame! [p height rows-drawn]
  (let [(y0 y1) (progress.rows p height)]
    (for [y y0 (- y1 1)] (tset rows-drawn (+ y 1) true))
    (progress.drawn! p)
    (- y1 y0)))

(describe "progressive rendering"
  (fn []
    (it "draws a whole pass in bands that cover every row once"
      (fn []
        (let [p (progress.new)
              rows {}
              counts []]
          (for [_ 1 p.bands]
            (let [(y0 y1) (progress.rows p 101)]
              (for [y y0 (- y1 1)] (tset counts (+ y 1) (+ 1 (or (. counts (+ y 1)) 0))))
              (progress.drawn! p)))
          (for [y 1 101] (assert.are.equal 1 (. counts y) (.. "row " y)))
          (assert.is_true (progress.complete? p)))))

    (it "splits further, in proportion, after one slow frame, and merges when fast"
      (fn []
        (let [p (progress.new)]
          (progress.measured! p 3.0)          ; 30x the budget: at most 16x more bands
          (assert.are.equal 64 p.bands)
          (progress.measured! p 60)
          (assert.are.equal progress.max-bands p.bands)
          (progress.measured! p 0.05)         ; within budget: stays
          (assert.are.equal progress.max-bands p.bands)
          (for [_ 1 20] (progress.measured! p 0.001))
          (assert.are.equal 1 p.bands))))

    (it "bounds one frame's rows by the band count, and completes only when every row is drawn"
      (fn []
        ;; A seeded walk through frame times, slow and fast, changing the band count
        ;; mid-pass: whenever the schedule says complete, every row was drawn.
        (var seed 12345)
        (fn rand [] (set seed (% (* seed 16807) 2147483647)) (/ seed 2147483647))
        (for [_ 1 50]
          (let [p (progress.new)
                rows {}
                height 300]
            (var frames 0)
            (while (not (progress.complete? p))
              (set frames (+ frames 1))
              (assert.is_true (< frames 5000) "never completes")
              (let [n (draw-frame! p height rows)]
                (assert.is_true (<= n (math.ceil (/ height p.bands))))
                (progress.measured! p (* (rand) (rand) 2))))
            (for [y 1 height] (assert.is_true (= true (. rows y)) (.. "row " y " not drawn")))))))

    (it "starts with as many bands as a known frame time needs"
      (fn []
        ;; A whole picture of 1.3 s (flower at 1280x720 on llvmpipe): 13 bands of 0.1 s.
        (assert.are.equal 13 (progress.bands-for 1.3))
        (assert.are.equal 1 (progress.bands-for 0.01))
        (assert.are.equal progress.max-bands (progress.bands-for 1000))
        (assert.are.equal 13 (. (progress.new (progress.bands-for 1.3)) :bands))
        (assert.are.equal 4 (. (progress.new) :bands))))))

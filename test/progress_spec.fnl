;; tier: fast
;; Progressive refinement's schedule (src/app/progress.fnl): a picture drawn in bands
;; from the top, each as tall as fits the budget at the measured time a row, render
;; times fed in (no clock, no GPU).
(local progress (require :src.app.progress))

(fn refine [p per-row ?limit]
  "Draw `p` to the end, each row taking (per-row y) seconds; the bands drawn."
  (let [drawn []]
    (while (and (not (progress.complete? p)) (< (length drawn) (or ?limit 10000)))
      (let [(y0 y1) (progress.rows p)
            seconds (accumulate [s 0 _ y (ipairs (fcollect [y y0 (- y1 1)] y))] (+ s (per-row y)))]
        (table.insert drawn [y0 y1 seconds])
        (progress.drawn! p y0 y1 seconds)))
    drawn))

(describe "progressive refinement"
  (fn []
    (it "draws every row once, from the top, and then is complete"
      (fn []
        (let [p (progress.new 101)
              counts {}]
          (each [_ [y0 y1] (ipairs (refine p #0.001))]
            (for [y y0 (- y1 1)] (tset counts y (+ 1 (or (. counts y) 0)))))
          (for [y 0 100] (assert.are.equal 1 (. counts y) (.. "row " y)))
          (assert.is_true (progress.complete? p))
          (assert.are.equal 1 (progress.covered p)))))

    (it "starts with as many bands as a predicted whole picture needs"
      (fn []
        ;; 1.3 s for the whole picture (flower at 1280x720 on llvmpipe): 13 bands.
        (assert.are.equal 13 (progress.bands (progress.new 720 1.3)))
        (assert.are.equal 1 (progress.bands (progress.new 720 0.01)))
        (assert.are.equal 4 (progress.bands (progress.new 720)))
        ;; A smaller budget for the render (the frame's other work took the rest).
        (assert.are.equal 26 (progress.bands (progress.new 720 1.3 0.05)))))

    (it "sizes each band to the budget at the time a row took in the one before"
      (fn []
        ;; 10 ms a row: 10 rows fit in 0.1 s, whatever the prediction said.
        (let [p (progress.new 720 100)
              bands (refine p #0.01)]
          (assert.are.equal 10 (- (. bands 2 2) (. bands 2 1)))
          (each [i [_ _ seconds] (ipairs bands)]
            (when (> i 1)
              (assert.is_true (<= seconds (+ progress.budget 1e-9)) (.. "band " i ": " seconds)))))))

    (it "keeps bands within the budget when the cost changes down the picture"
      (fn []
        ;; The top is sky (cheap), the bottom a heavy surface: one band may overshoot
        ;; where the cost jumps, the next is sized again.
        (let [p (progress.new 720 1)
              bands (refine p #(if (< $1 300) 1e-4 0.02))
              over (icollect [_ [_ _ s] (ipairs bands)] (when (> s (* 1.01 progress.budget)) s))]
          (assert.is_true (progress.complete? p))
          (assert.is_true (<= (length over) 1) (.. (length over) " bands over the budget")))))

    (it "weighs a later pass's share by an earlier pass's time a row"
      (fn []
        ;; The top 300 rows sky (0.1 ms a row), the rest a heavy surface (20 ms):
        ;; half the rows are well under half the work. The earlier pass in even
        ;; bands (32 of 23 rows, as --render draws its centre rays).
        (let [cost #(if (< $1 300) 1e-4 0.02)
              even (progress.new 720 8 0.25 true)
              passed (refine even cost)
              sum (fn [y] (accumulate [s 0 _ r (ipairs (fcollect [r 0 (- y 1)] r))] (+ s (cost r))))
              total (sum 720)
              above (fn [y] (/ (sum y) total))]
          (assert.are.equal 0 (progress.share-above passed 0))
          (assert.are.equal 1 (progress.share-above passed 720))
          ;; Within a band, its time is spread evenly over its rows: the share is
          ;; exact at band edges, and near where a band mixes sky and surface.
          (each [_ [_ y1] (ipairs passed)]
            (assert.is_true (< (math.abs (- (above y1) (progress.share-above passed y1))) 1e-9)
                            (.. "row " y1)))
          (assert.is_true (< (progress.share-above passed 360) 0.2))
          (assert.is_true (< (math.abs (- (above 360) (progress.share-above passed 360))) 0.01))
          ;; Even bands: all as tall as the first.
          (assert.are.equal 32 (length passed))
          (each [_ [y0 y1] (ipairs passed)]
            (assert.is_true (<= (- y1 y0) 23)))
          ;; A pass that took no time tells nothing.
          (assert.is_nil (progress.share-above [[0 720 0]] 360)))))

    (it "never draws fewer than 1/256 of the picture a band, nor more than all of it"
      (fn []
        (let [p (progress.new 1024)]
          (progress.drawn! p 0 4 1000)
          (assert.are.equal 4 p.rows)
          (progress.drawn! p 4 8 0)
          (assert.are.equal 1024 p.rows))))))

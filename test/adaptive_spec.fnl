;; tier: fast
;; The player's frame-time model (src/app/adaptive.fnl): the picture drawn while the
;; state changes is sized from measured renders to meet the target frame time, with
;; the time no scale changes (the window, the HUD) taken off first.

(local adaptive (require :src.app.adaptive))

(local window (* 1280 720))
(local target (/ 1 30))

(fn frame! [a shader scale cost-of fixed]
  ;; One frame at `scale` whose render takes (cost-of pixels), the frame `fixed` more.
  (let [pixels (* scale scale window)
        seconds (cost-of pixels)]
    (adaptive.measured! a shader pixels seconds (+ seconds fixed))
    (+ seconds fixed)))

(fn settle [cost-of fixed]
  ;; Thirty frames, each at the scale the model asks for; the last frame's time.
  (let [a (adaptive.new)]
    (var scale (adaptive.scale-for a :s target window 1))
    (var last 0)
    (for [_ 1 30]
      (set last (frame! a :s scale cost-of fixed))
      (set scale (adaptive.scale-for a :s target window 1)))
    (values last scale a)))

(describe "adaptive resolution"
  (fn []
    (it "meets the target frame time when the render is all in proportion to pixels"
      (fn []
        ;; 1 s for the whole window: 1/30 s needs scale sqrt(1/30) = 0.183.
        (let [(last scale) (settle #(/ $1 window) 0)]
          (assert.is_true (< (math.abs (- last target)) (* 0.01 target)) (tostring last))
          (assert.is_true (< (math.abs (- scale (math.sqrt (/ 1 30)))) 1e-3) (tostring scale)))))

    (it "takes the frame's other work and the render's own offset off before sizing"
      (fn []
        ;; 12 ms a frame that no scale changes, 4 ms a render whatever its size: a
        ;; model in proportion to pixels alone would miss the target by their sum.
        (let [(last _ a) (settle #(+ 0.004 (/ $1 window)) 0.012)]
          (assert.is_true (< (math.abs (- last target)) (* 0.05 target))
                          (string.format "%.1f ms for a %.1f ms target" (* 1000 last) (* 1000 target)))
          (assert.is_false a.out-of-reach?))))

    (it "says the target is out of reach when the other work alone takes longer"
      (fn []
        (let [(_ scale a) (settle #(/ $1 window) 0.05)]
          (assert.is_true a.out-of-reach?)
          (assert.are.equal adaptive.min-scale scale))))

    (it "never goes above the chosen scale, and starts small for a shader not measured"
      (fn []
        (let [a (adaptive.new)]
          (assert.are.equal adaptive.first-scale (adaptive.scale-for a :new target window 1))
          (assert.are.equal 0.1 (adaptive.scale-for a :new target window 0.1))
          (adaptive.rendered! a :cheap 100 1e-6)
          (assert.are.equal 0.5 (adaptive.scale-for a :cheap target window 0.5)))))

    (it "fits an offset and a slope from renders of two sizes"
      (fn []
        (let [a (adaptive.new)]
          (adaptive.rendered! a :s 144 (+ 0.002 (* 144 1e-5)))
          (adaptive.rendered! a :s 2304 (+ 0.002 (* 2304 1e-5)))
          (let [predicted (adaptive.render-seconds a :s 10000)]
            (assert.is_true (< (math.abs (- predicted 0.102)) 1e-6) (tostring predicted))))))

    (it "keeps one model a shader"
      (fn []
        (let [a (adaptive.new)]
          (adaptive.rendered! a :light 1000 0.001)
          (adaptive.rendered! a :heavy 1000 0.01)
          (assert.is_true (> (adaptive.scale-for a :light target window 1)
                             (* 3 (adaptive.scale-for a :heavy target window 1)))))))))

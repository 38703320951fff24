;; The player's adaptive resolution (src/app/adaptive.fnl): the moving scale meets the
;; target frame time, and the camera's moving and stopping are told apart.

(local adaptive (require :src.app.adaptive))

(describe "adaptive resolution"
  (fn []
    (it "lowers the scale toward the target frame time, with frame time as pixels"
      (fn []
        ;; A frame at scale 1 takes 1 s; 1/30 s needs scale sqrt(1/30) = 0.183.
        (var scale 1)
        (for [_ 1 30]
          (let [seconds (* scale scale 1)]
            (set scale (adaptive.next-scale scale seconds (/ 1 30) 1))))
        (assert.is_true (< (math.abs (- scale (math.sqrt (/ 1 30)))) 1e-3) (tostring scale))))

    (it "never goes above the chosen scale or below 0.05"
      (fn []
        (assert.are.equal 0.5 (adaptive.next-scale 0.5 0.0001 (/ 1 30) 0.5))
        (assert.are.equal 0.05 (adaptive.next-scale 0.05 100 (/ 1 30) 1))))

    (it "tells moving, stopping and still frames apart"
      (fn []
        (let [a (adaptive.new 1)
              cam {:pos [0 0 0] :yaw 0 :pitch 0 :fov 60}]
          (assert.are.equal :still (adaptive.update! a cam 0.1 (/ 1 30) 1))
          (set cam.yaw 1)
          (assert.are.equal :moving (adaptive.update! a cam 0.1 (/ 1 30) 1))
          (set cam.yaw 2)
          (assert.are.equal :moving (adaptive.update! a cam 0.1 (/ 1 30) 1))
          (assert.are.equal :stopped (adaptive.update! a cam 0.1 (/ 1 30) 1))
          (assert.are.equal :still (adaptive.update! a cam 0.1 (/ 1 30) 1)))))))

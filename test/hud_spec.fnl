;; tier: fast
;; The HUD's camera line (src/app/hud.fnl): its pitch reads as the keys say.
(local hud (require :src.app.hud))
(local camera (require :src.render.camera))

(describe "the HUD's camera line"
  (fn []
    (it "says up after e (pitch up) and down after q (pitch down)"
      (fn []
        ;; The player's keys: q pitches by +degrees, e by -degrees (camera.pitch!).
        (let [cam {:pos [1 2 3] :yaw 90 :pitch 0 :fov 60}]
          (assert.are.equal "pos: 1.00 2.00 3.00  yaw 90.0  pitch 0.0" (hud.camera-line cam))
          (camera.pitch! cam -12)           ; e held
          (assert.are.equal "pos: 1.00 2.00 3.00  yaw 90.0  pitch 12.0 up" (hud.camera-line cam))
          ;; Up means looking up: the forward vector climbs.
          (assert.is_true (> (. (camera.forward cam) 3) 0))
          (camera.pitch! cam 20)            ; q held
          (assert.are.equal "pos: 1.00 2.00 3.00  yaw 90.0  pitch 8.0 down" (hud.camera-line cam))
          (assert.is_true (< (. (camera.forward cam) 3) 0)))))

    (it "shows no direction for a pitch that rounds to 0.0"
      (fn []
        (assert.are.equal "0.0" (hud.pitch-text 0.04))
        (assert.are.equal "0.0" (hud.pitch-text -0.04))
        (assert.are.equal "89.9 up" (hud.pitch-text -89.9))))))

;; tier: fast
;; Specs for src/render/camera.fnl: the article's forward vector and basis, primary rays,
;; movement and the clamps on pitch, yaw and field of view.
(local camera (require :src.render.camera))

(local rad (/ math.pi 180))

(fn near [expected actual ?tol]
  (let [tol (or ?tol 1e-12)]
    (assert (<= (math.abs (- expected actual)) tol)
            (.. "expected " (tostring expected) " got " (tostring actual)))))

(fn near3 [[ex ey ez] [ax ay az] ?tol]
  (near ex ax ?tol) (near ey ay ?tol) (near ez az ?tol))

(fn dot [[ax ay az] [bx by bz]] (+ (* ax bx) (* ay by) (* az bz)))

(fn cam [yaw pitch ?fov ?pos]
  {:pos (or ?pos [0 0 0]) :yaw yaw :pitch pitch :fov (or ?fov 60)})

(describe "camera: orientation"
  (fn []
    (it "points forward as the article's rotation at yaw 255, pitch 15"
      (fn []
        (let [f (camera.forward (cam 255 15))]
          (near3 [(* (math.cos (* 255 rad)) (math.cos (* 15 rad)))
                  (* (math.sin (* 255 rad)) (math.cos (* 15 rad)))
                  (- (math.sin (* 15 rad)))]
                 f)
          ;; Numerically: looking back toward the origin from [20 50 20], slightly down.
          (near -0.25 (. f 1) 0.01)
          (near -0.933 (. f 2) 0.001)
          (near -0.2588 (. f 3) 0.0001))))

    (it "looks along the axes at the cardinal yaws"
      (fn []
        (near3 [1 0 0] (camera.forward (cam 0 0)))
        (near3 [0 1 0] (camera.forward (cam 90 0)))
        (near3 [-1 0 0] (camera.forward (cam 180 0)))
        (near3 [0 -1 0] (camera.forward (cam 270 0)))
        ;; Positive pitch looks down.
        (near3 [(math.cos (* 45 rad)) 0 (- (math.sin (* 45 rad)))] (camera.forward (cam 0 45)))))

    (it "builds an orthonormal basis"
      (fn []
        (each [_ [y p] (ipairs [[255 15] [0 0] [33 -60] [180 89.9] [359 -89.9]])]
          (let [(f r u) (camera.basis (cam y p))]
            (near 1 (dot f f) 1e-12)
            (near 1 (dot r r) 1e-12)
            (near 1 (dot u u) 1e-12)
            (near 0 (dot f r) 1e-12)
            (near 0 (dot f u) 1e-12)
            (near 0 (dot r u) 1e-12)
            ;; Right stays in the ground plane.
            (near 0 (. r 3) 1e-12)))))

    (it "has right = -y and up = -z looking level along +x (pixel y grows down)"
      (fn []
        (let [(f r u) (camera.basis (cam 0 0))]
          (near3 [1 0 0] f)
          (near3 [0 -1 0] r)
          (near3 [0 0 -1] u))
        (let [(_ r u) (camera.basis (cam 90 0))]
          (near3 [1 0 0] r)
          (near3 [0 0 -1] u))))

    (it "has the projection distance 1 / tan(fov / 2)"
      (fn []
        (near (math.sqrt 3) (camera.projection-distance (cam 0 0 60)))
        (near 1 (camera.projection-distance (cam 0 0 90)))
        (near (/ 1 (math.tan (* 10 rad))) (camera.projection-distance (cam 0 0 20)))))))

(describe "camera: primary rays"
  (fn []
    (it "sends the centre pixel along forward"
      (fn []
        (each [_ [w h] (ipairs [[640 480] [1 1] [1920 1080] [100 300]])]
          (let [c (cam 255 15)]
            (near3 (camera.forward c) (camera.ray-direction c (/ w 2) (/ h 2) w h) 1e-12)))))

    (it "goes right for pixels right of centre and down for pixels below"
      (fn []
        (let [c (cam 0 0 90)
              (_ r u) (camera.basis c)
              right (camera.ray-direction c 640 240 640 480)
              below (camera.ray-direction c 320 480 640 480)]
          (assert.is_true (> (dot right r) 0))
          (assert.is_true (> (dot below u) 0))
          ;; Down the screen is -z in the world.
          (assert.is_true (< (. below 3) 0))
          ;; fov 90: the top edge is 0.5 up over projection distance 1.
          (near3 (let [l (math.sqrt 1.25)] [(/ 1 l) 0 (/ 0.5 l)])
                 (camera.ray-direction c 320 0 640 480))
          ;; Horizontal uv spans the aspect ratio: right edge at 0.5 * 640/480.
          (let [x (* 0.5 (/ 640 480)) l (math.sqrt (+ 1 (* x x)))]
            (near3 [(/ 1 l) (/ (- x) l) 0] right)))))

    (it "returns unit vectors"
      (fn []
        (let [c (cam 255 15 60)]
          (each [_ [x y] (ipairs [[0 0] [639.5 0.5] [17 400]])]
            (near 1 (dot (camera.ray-direction c x y 640 480) (camera.ray-direction c x y 640 480))
                  1e-12)))))))

(describe "camera: state and movement"
  (fn []
    (it "copies its state from a scene"
      (fn []
        (let [s {:camera {:pos [20 50 20] :yaw 255 :pitch 15 :fov 60}}
              c (camera.from-scene s)]
          (assert.are.same {:pos [20 50 20] :yaw 255 :pitch 15 :fov 60} c)
          (camera.elevate! c 1)
          (assert.are.same [20 50 20] s.camera.pos))))

    (it "moves forward along the view direction"
      (fn []
        (let [c (cam 0 0 60 [1 2 3])]
          (camera.move-forward! c 2)
          (near3 [3 2 3] c.pos))
        (let [c (cam 255 15 60 [20 50 20])
              f (camera.forward c)]
          (camera.move-forward! c -10)
          (near3 [(- 20 (* 10 (. f 1))) (- 50 (* 10 (. f 2))) (- 20 (* 10 (. f 3)))] c.pos))))

    (it "strafes right to -y when facing +x, in the ground plane"
      (fn []
        (let [c (cam 0 30 60 [0 0 5])]
          (camera.strafe! c 1)
          (near3 [0 -1 5] c.pos))
        (let [c (cam 90 0)]
          (camera.strafe! c 2)
          (near3 [2 0 0] c.pos))
        ;; Strafing right follows the camera's right vector.
        (let [c (cam 255 15)
              (_ r) (camera.basis c)]
          (camera.strafe! c 1)
          (near3 r c.pos))))

    (it "elevates straight up and down"
      (fn []
        (let [c (cam 123 45 60 [1 2 3])]
          (camera.elevate! c 2.5)
          (assert.are.same [1 2 5.5] c.pos)
          (camera.elevate! c -10)
          (assert.are.same [1 2 -4.5] c.pos))))

    (it "turns right by decreasing yaw, wrapping mod 360"
      (fn []
        (let [c (cam 5 0)]
          (camera.turn! c 10)
          (assert.are.equal 355 c.yaw)
          (camera.turn! c -10)
          (assert.are.equal 5 c.yaw)
          (camera.turn! c -360)
          (assert.are.equal 5 c.yaw)
          (camera.turn! c -725)
          (assert.are.equal 10 c.yaw)
          (camera.turn! c 10)
          (assert.are.equal 0 c.yaw))))

    (it "clamps pitch at +-89.9 degrees"
      (fn []
        (let [c (cam 0 80)]
          (camera.pitch! c 5)
          (assert.are.equal 85 c.pitch)
          (camera.pitch! c 20)
          (assert.are.equal 89.9 c.pitch)
          (camera.pitch! c -500)
          (assert.are.equal -89.9 c.pitch)
          (camera.pitch! c 0.9)
          (near -89 c.pitch 1e-12))))

    (it "clamps the field of view to 1..179"
      (fn []
        (let [c (cam 0 0 60)]
          (camera.zoom! c 30)
          (assert.are.equal 90 c.fov)
          (camera.zoom! c 200)
          (assert.are.equal 179 c.fov)
          (camera.zoom! c -500)
          (assert.are.equal 1 c.fov))))))

(describe "camera: turntable orbit"
  (fn []
    (it "keeps height and distance, and looks at the centre"
      (fn []
        (let [cam {:pos [10 0 5] :yaw 0 :pitch 0 :fov 60}
              c [0 0 1]
              o (camera.orbit cam c 90)
              [x y z] o.pos
              [fx fy fz] (camera.forward o)
              ;; The unit vector from the camera to the centre.
              (dx dy dz) (values (- 0 x) (- 0 y) (- 1 z))
              len (math.sqrt (+ (* dx dx) (* dy dy) (* dz dz)))]
          (assert.is_true (< (math.abs x) 1e-9))
          (assert.is_true (< (math.abs (- y 10)) 1e-9))
          (assert.are.equal 5 z)
          (assert.is_true (< (math.abs (- fx (/ dx len))) 1e-9))
          (assert.is_true (< (math.abs (- fy (/ dy len))) 1e-9))
          (assert.is_true (< (math.abs (- fz (/ dz len))) 1e-9))
          ;; The original camera is left alone.
          (assert.are.same [10 0 5] cam.pos))))))

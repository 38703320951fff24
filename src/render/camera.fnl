;; The article's fly camera: position, yaw (the article's x-rotate) and pitch (its
;; z-rotate) in degrees, z up. Pure math on plain tables, in double precision.

(local rad (/ math.pi 180))

(fn forward [cam]
  "Unit forward vector: the article's rotate-point of [1 0 0] by yaw and pitch.
Positive pitch looks down, as in the article."
  (let [yaw (* cam.yaw rad)
        pitch (* cam.pitch rad)]
    [(* (math.cos yaw) (math.cos pitch))
     (* (math.sin yaw) (math.cos pitch))
     (- (math.sin pitch))]))

(fn cross [[ax ay az] [bx by bz]]
  [(- (* ay bz) (* az by))
   (- (* az bx) (* ax bz))
   (- (* ax by) (* ay bx))])

(fn normalize [[x y z]]
  (let [len (math.sqrt (+ (* x x) (* y y) (* z z)))]
    [(/ x len) (/ y len) (/ z len)]))

(fn basis [cam]
  "Forward, right and up vectors of the camera. `up` points down the screen (pixel y
grows downwards), as in the article. The article's right = normalize(cross([0 0 -1],
forward)) is (sin yaw, -cos yaw, 0) whenever it is defined; written that way it also
holds looking straight up or down (pitch +-90), where the cross product vanishes: the
article's camera is then NaN for an exactly vertical forward (and in float32), and in
double it survives only because cos(90 degrees) rounds to 6e-17. up = cross(forward,
right)."
  (let [f (forward cam)
        yaw (* cam.yaw rad)
        r [(math.sin yaw) (- (math.cos yaw)) 0]
        u (cross f r)]
    (values f r u)))

(fn article-basis [cam]
  "The article's own construction, kept to show where it fails (vertical forward)."
  (let [f (forward cam)
        r (normalize (cross [0 0 -1] f))]
    (values f r (cross f r))))

(fn projection-distance [cam]
  "Distance to the projection plane: 1 / tan(fov / 2)."
  (/ 1 (math.tan (* cam.fov 0.5 rad))))

(fn ray-direction [cam x y width height]
  "Unit direction of the primary ray through pixel position (x, y), y down; pixel
centres are at +0.5."
  (let [(f r u) (basis cam)
        pd (projection-distance cam)
        uvx (* (- (/ x width) 0.5) (/ width height))
        uvy (- (/ y height) 0.5)]
    (normalize [(+ (* (. f 1) pd) (* (. r 1) uvx) (* (. u 1) uvy))
                (+ (* (. f 2) pd) (* (. r 2) uvx) (* (. u 2) uvy))
                (+ (* (. f 3) pd) (* (. r 3) uvx) (* (. u 3) uvy))])))

(fn from-scene [scene]
  "A fresh camera state from the scene's :camera section."
  (let [c scene.camera]
    {:pos [(. c.pos 1) (. c.pos 2) (. c.pos 3)] :yaw c.yaw :pitch c.pitch :fov c.fov}))

(fn clamp [x lo hi] (math.max lo (math.min hi x)))

;;; Movement, as the article's controls do it; amounts are already scaled by dt.

(fn move-forward! [cam amount]
  "Move along the view direction."
  (let [f (forward cam)]
    (for [i 1 3] (tset cam.pos i (+ (. cam.pos i) (* (. f i) amount))))))

(fn strafe! [cam amount]
  "Move sideways in the ground plane; positive is to the right."
  (let [yaw (* (- cam.yaw 90) rad)]
    (tset cam.pos 1 (+ (. cam.pos 1) (* (math.cos yaw) amount)))
    (tset cam.pos 2 (+ (. cam.pos 2) (* (math.sin yaw) amount)))))

(fn elevate! [cam amount]
  "Move straight up (positive) or down."
  (tset cam.pos 3 (+ (. cam.pos 3) amount)))

(fn turn! [cam degrees]
  "Turn right by `degrees` (the article's camera-rotate-x: yaw decreases)."
  (set cam.yaw (% (- cam.yaw degrees) 360)))

(fn pitch! [cam degrees]
  "Pitch by `degrees`, positive looks down, kept within the article's +-89.9."
  (set cam.pitch (clamp (+ cam.pitch degrees) -89.9 89.9)))

(fn zoom! [cam degrees]
  "Widen the field of view by `degrees`, kept within 1 to 179."
  (set cam.fov (clamp (+ cam.fov degrees) 1 179)))

(fn orbit [cam [cx cy cz] degrees]
  "A copy of `cam` turned `degrees` about the vertical axis through c (keeping its
height and horizontal distance) and looking at c: a turntable's camera."
  (let [[px py pz] cam.pos
        dx (- px cx) dy (- py cy)
        r (math.sqrt (+ (* dx dx) (* dy dy)))
        a (+ (math.atan2 dy dx) (* degrees rad))
        x (+ cx (* r (math.cos a)))
        y (+ cy (* r (math.sin a)))]
    {:pos [x y pz]
     ;; Facing the centre: the yaw of the direction back to it; pitch down by the
     ;; angle of the drop to it (positive looks down).
     :yaw (% (/ (math.atan2 (- cy y) (- cx x)) rad) 360)
     :pitch (clamp (/ (math.atan2 (- pz cz) (math.max r 1e-9)) rad) -89.9 89.9)
     :fov cam.fov}))

{: forward : basis : article-basis : orbit : projection-distance : ray-direction : from-scene
 : move-forward! : strafe! : elevate! : turn! : pitch! : zoom!}

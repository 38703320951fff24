;; `love . --record SCENE --out DIR --frames N [--fps F] [--size WxH] [--turntable]
;; [--quality Q] [--samples N]`: frames at t = i / F written as DIR/frame-0001.png ...,
;; deterministically (the same command gives the same files), with progress on
;; stderr. Each frame is the player's anti-aliased still unless --quality or
;; --samples says otherwise (src/app/quality.fnl), drawn in bands as --render does.
;; --turntable orbits the camera once around the scene's centre over the recording.

(local status (require :src.util.status))
(local stop (require :src.app.stop))
(local frame (require :src.backend.frame))
(local gpu (require :src.backend.gpu))
(local camera (require :src.render.camera))
(local output (require :src.util.output))
(local quality (require :src.app.quality))
(local render (require :src.app.render))

(fn scene-centre [scene]
  "The middle of the box around the objects' placements (planes and unplaced trees
excepted), or a point 10 units in front of the camera when there is none."
  (let [points (icollect [_ o (ipairs scene.objects)]
                 (if (and o.tree o.tree.pos) o.tree.pos
                     (and o.tree (= o.tree.kind :translate)) o.tree.offset
                     o.pos))]
    (if (= (length points) 0)
        (let [[x y z] scene.camera.pos
              [fx fy fz] (camera.forward (camera.from-scene scene))]
          [(+ x (* 10 fx)) (+ y (* 10 fy)) (+ z (* 10 fz))])
        (fcollect [i 1 3]
          (let [lo (accumulate [m math.huge _ p (ipairs points)] (math.min m (. p i)))
                hi (accumulate [m (- math.huge) _ p (ipairs points)] (math.max m (. p i)))]
            (* 0.5 (+ lo hi)))))))

(fn run [o]
  "Record o.frames frames of o.scene into o.out. Returns true, or nil and a message."
  (case (frame.load-scene o.scene)
    (nil err) (values nil err)
    scene
    ;; Values that never change are constants in the code; functions of time keep
    ;; theirs as uniforms (one shader for every frame).
    (case (frame.plan-for scene (quality.plan-options
                                  o scene {:fold? (not ((. (require :src.scene.load) :animated?) scene))}))
      (nil err) (values nil err)
      plan
      (let [rays (quality.resolve o scene)
            [w h] (or o.size [640 360])
            fps (or o.fps 30)
            cache (gpu.new-cache)
            canvas (love.graphics.newCanvas w h)
            cam0 (camera.from-scene scene)
            centre (scene-centre scene)
            scene-mod (require :src.scene.load)
            worker (require :src.scene.worker)]
        (var err (case (output.ensure-dir! o.out {:label (.. "--out " o.out)})
                   (nil e) e))
        (for [i 0 (- o.frames 1) &until err]
          ;; Functions of time take their values at t = i / fps; the plan is lowered
          ;; again for them (values only: the shader stays).
          (let [t (/ i fps)
                (animated-ok? aerr) (if (scene-mod.animated? scene) (worker.animate scene t) true)
                (plan perr) (if (not animated-ok?) (values nil aerr)
                                (scene-mod.animated? scene)
                                (frame.plan-for scene (quality.plan-options o scene))
                                plan)
                cam (if o.turntable? (camera.orbit cam0 centre (/ (* 360 i) o.frames))
                        (camera.from-scene scene))
                path (string.format "%s/frame-%04d.png" o.out (+ i 1))]
            (case (if (stop.asked?) (values nil stop.message)
                      plan (render.draw! cache canvas scene plan cam #(when (stop.asked?) :stop)
                                         (= rays.quality :still))
                      (values nil perr))
              (nil e) (set err e)
              _ (case (frame.write-png canvas path {:protect [o.scene]})
                  (nil e) (set err e)))
            (status.update! (string.format "frame %d/%d (t = %.3f s)" (+ i 1) o.frames (/ i fps)))))
        (status.done!)
        (if (= err stop.message)
            ;; The frames written are whole files: kept, and said.
            (values nil (string.format "--record: %s; the frames written before are kept (%s/frame-0001.png ...)"
                                       err o.out))
            err (values nil err)
            (do (print (string.format "wrote %d frames of %dx%d (%s) to %s/frame-0001.png ..."
                                      o.frames w h rays.label o.out))
                true))))))

{: run}

;; `love . --render SCENE --out FILE.png [--size WxH] [--view VIEW] [--quality Q]
;; [--samples N]`: one finished picture, by default the player's anti-aliased still
;; (src/app/quality.fnl), drawn in bands from the top as the player draws its still:
;; no single draw runs for seconds (a GPU's watchdog), and a long render shows its
;; progress on stderr. --record draws its frames the same way.

(local status (require :src.util.status))
(local stop (require :src.app.stop))
(local scene-mod (require :src.scene.load))
(local worker (require :src.scene.worker))
(local frame (require :src.backend.frame))
(local gpu (require :src.backend.gpu))
(local camera (require :src.render.camera))
(local output (require :src.util.output))
(local progress (require :src.app.progress))
(local quality (require :src.app.quality))
(local uniforms (require :src.render.uniforms))

;; Seconds a band may take (its rows are sized by the time a row took before), and
;; the bands a picture starts with before any is timed.
(local band-seconds 0.25)
(local first-bands 32)
;; Progress is shown once a render has taken this long, at most twice a second.
(local quiet-seconds 1)
(local report-every 0.5)

(fn wait-for! [canvas]
  ;; Reading one pixel back waits for the renderer to finish what it was given.
  (let [data (canvas:newImageData 1 1 0 0 1 1)] (data:release)))

(fn prepare! [cache scene plan cam]
  "Compile `plan`'s shader and draw it once into a 1x1 canvas: the driver builds the
code it runs at its first draw, which is not the picture's time. True, or nil and
a message."
  (let [canvas (love.graphics.newCanvas 1 1)
        (ok? err) (frame.render-to-canvas! cache canvas scene plan cam)]
    (when ok? (wait-for! canvas))
    (canvas:release)
    (if ok? true (values nil err))))

(fn draw! [cache canvas scene plan cam ?on-band ?prior?]
  "Draw `scene` (lowered to `plan`, seen by `cam`) into `canvas` in bands from the
top, each about band-seconds. `(?on-band covered seconds)` runs after each band:
the share done (0 to 1: of the rows; once the centre rays are drawn, of the time,
by their times a row) and the seconds since the first; when it returns :stop the
drawing stops there. With `?prior?` (an adaptive plan drawn as the player's still),
the picture of the centre rays is drawn first, as the player has it, and the still
reads it (uniforms.prior). The seconds it took, or nil and a message."
  (let [(w h) (canvas:getDimensions)
        start (love.timer.getTime)
        prior (when ?prior? (love.graphics.newCanvas w h))]
    (var err nil)
    (fn bands! [target extra share-from share ?even? ?passed]
      ;; One pass over the picture (`?even?`: in first-bands bands of one height);
      ;; its bands [y0 y1 seconds]. After `?passed` (an earlier pass's bands) its
      ;; share done is weighed by their time a row, and the whole's share done is
      ;; the share of the time: what has been spent over that plus what this pass
      ;; still needs at its own rate.
      (let [p (progress.new h (* first-bands band-seconds) band-seconds ?even?)
            pass-start (love.timer.getTime)
            drawn []
            done (fn [y1]
                   (case (and ?passed (progress.share-above ?passed y1))
                     (where s (> s 0))
                     (let [now (love.timer.getTime)
                           left (* (- now pass-start) (/ (- 1 s) s))
                           spent (- now start)]
                       (/ spent (math.max 1e-9 (+ spent left))))
                     _ (+ share-from (* share (progress.covered p)))))]
        (while (and (not err) (not (progress.complete? p)))
          (let [(y0 y1) (progress.rows p)
                t0 (love.timer.getTime)]
            (case (frame.render-to-canvas! cache target scene plan cam [y0 y1] extra)
              (nil e) (set err e)
              _ (do (wait-for! target)
                    (let [seconds (- (love.timer.getTime) t0)]
                      (table.insert drawn [y0 y1 seconds])
                      (progress.drawn! p y0 y1 seconds)
                      (when (and ?on-band
                                 (= :stop (?on-band (done y1) (- (love.timer.getTime) start))))
                        (set err stop.message)))))))
        drawn))
    (if prior
        (do (prior:setFilter :nearest :nearest)
            ;; The centre rays are one of the still's 2 to 17 a pixel: a tenth of the
            ;; work, drawn in even bands. The still's rays cost as its centre rays
            ;; did, row by row (sky rows are cheap in both): its share done is
            ;; weighed by their times, so that its time left is not read from the
            ;; sky at the top.
            (let [centre (bands! prior (uniforms.prior 1) 0 0.1 true)]
              (bands! canvas (uniforms.prior 2 prior) 0.1 0.9 false centre))
            (prior:release))
        (bands! canvas nil 0 1))
    (if err (values nil err) (- (love.timer.getTime) start))))

(fn reporter [what]
  "An ?on-band for draw! that shows `what`'s progress on stderr once it has taken
quiet-seconds, at most twice a second, and whether it showed any (call it with no
arguments); it stops the drawing on SIGINT or SIGTERM (src/app/stop.fnl)."
  (var last nil)
  (var shown? false)
  (fn [covered seconds]
    (if (= covered nil)
        shown?
        (stop.asked?)
        :stop
        (when (and (>= seconds quiet-seconds) (< covered 1)
                   (or (= last nil) (>= (- seconds last) report-every)))
          (set last seconds)
          (set shown? true)
          (let [left (* seconds (/ (- 1 covered) (math.max covered 1e-9)))]
            (status.update! (string.format "%s: %d%%, %.1f s, %s left" what
                                           (math.floor (* 100 covered)) seconds
                                           (if (< left 1) "under 1 s"
                                               (string.format "about %.0f s" left)))))))))

(fn out-options [o]
  ;; The command line's output: named as --out, never the scene file.
  {:protect [o.scene] :label (.. "--out " o.out)})

(fn load-at [path ?t]
  ;; The scene file `path` loaded, its functions of time at ?t seconds (their values
  ;; at 0 are the load's), or nil and a message.
  (case (frame.load-scene path)
    (nil err) (values nil err)
    (where scene (and ?t (not= ?t 0) (scene-mod.animated? scene)))
    (case (worker.animate scene ?t)
      (nil err) (values nil err)
      _ scene)
    scene scene))

(fn run [o]
  "Render o.scene into o.out (a PNG) at o.size (512x448) with o.view, o.quality and
o.samples (see quality.resolve), its functions of time at o.time seconds (0). Prints what it wrote; true, or nil and a message."
  ;; A refused --out is refused before the scene is even read.
  (case (output.check o.out (out-options o))
    (nil err) (values nil err)
    _
    (case (load-at o.scene o.time)
      (nil err) (values nil err)
      scene
      ;; One frame of values that never change: the trees' values as constants (but
      ;; with --interpret: the tape interpreter's shader, for its own set).
      (let [rays (quality.resolve o scene)]
        (case (frame.plan-for scene (quality.plan-options o scene {:view o.view :fold? true
                                                                   :interpret? o.interpret?}))
          (nil err) (values nil err)
          plan
          (let [[w h] (or o.size [512 448])
                cache (gpu.new-cache)
                cam (camera.from-scene scene)
                canvas (love.graphics.newCanvas w h)
                report (reporter (string.format "render %dx%d (%s)" w h rays.label))]
            (case (prepare! cache scene plan cam)
              (nil err) (values nil err)
              _ (case (draw! cache canvas scene plan cam report (= rays.quality :still))
                  (nil err) (do (when (report) (status.done!))
                                (values nil (if (= err stop.message)
                                                (.. "--render: " err "; nothing written")
                                                err)))
                  seconds
                  (do (when (report) (status.done!))
                      (case (frame.write-png canvas o.out (out-options o))
                        true (do (print (string.format "wrote %s (%dx%d, %s, %.2f s)" o.out w h
                                                       rays.label seconds))
                                 true)
                        (_ werr) (values nil werr)))))))))))

{: run : draw! : prepare! : reporter : band-seconds}

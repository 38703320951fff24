;; `love . --input-check`: drives the player through LÖVE's own event queue, as a
;; person at a slow machine would: a key tapped between two frames, a click after the
;; pointer moved with no button held, - before ] (another scene), F12, the
;; parameter panel (drag a slider, tick a switch, save into the file) and F9 (a mesh
;; of the scene as shown). Every event is
;; pushed with love.event.push and reaches the player through love.run, exactly like
;; real input; keyboard state (isDown) stays empty, as for a tap too short to be seen.

(local play (require :src.app.play))
(local camera (require :src.render.camera))
(local panel (require :src.app.panel))
(local files (require :src.util.files))
(local filestat (require :src.util.filestat))
(local warm (require :src.app.warm))
(local scripted (require :src.app.scripted))

(local scene-text
  ";; a scene for the input check: comments and odd layout stay as they are
{:name \"input check\"
 :camera {:pos [0 -8 1.5] :yaw 90 :pitch 0 :fov 60}
 :light {:pos [-6 -12 10]}
 :render {:reflections 1
          :shadows   (param :shadows true)}   ; a switch (it changes the shader)
 :objects [{:kind :sphere
            :radius (param :radius
                           1   {:min 0.5 :max 2})
            :pos [0 0 1] :color (param :tint [0.8 0.3 0.2])}
           {:kind :plane :height 0 :color [0.6 0.6 0.6]}]}
")

(fn distance [a b]
  (let [dx (- (. a 1) (. b 1)) dy (- (. a 2) (. b 2)) dz (- (. a 3) (. b 3))]
    (math.sqrt (+ (* dx dx) (* dy dy) (* dz dz)))))

(fn push-key [key]
  (love.event.push :keypressed key key false)
  (love.event.push :keyreleased key key))

(fn item-named [label]
  (let [lay (panel.layout play.state.scene.params (love.graphics.getWidth))]
    (accumulate [found nil _ item (ipairs lay.items) &until found]
      (when (= item.label label) item))))

(fn wait-while [cx busy? seconds]
  "Wait frame after frame while `busy?` holds, at most `seconds`."
  (let [until (+ (love.timer.getTime) seconds)]
    (while (and (busy?) (< (love.timer.getTime) until))
      (cx.wait))))

;;; The steps of the script, in order. Each takes the check's context: {:state (the
;;; player's) :path (the scene file) :check (fn [ok? what]) :wait (fn [?n]: yield
;;; ?n frames)}; the compile helper's steps also read its :warm.

(fn check-tapped-keys [{: state : wait : check}]
  "A tap: pressed and released between two updates, moving and then turning the
camera."
  (let [before [(. state.cam.pos 1) (. state.cam.pos 2) (. state.cam.pos 3)]]
    (push-key :w)
    (wait 2)
    (let [moved (distance before state.cam.pos)]
      (check (> moved 0.5) (string.format "a tapped key moves the camera (moved %.2f units)" moved))))
  (let [yaw state.cam.yaw]
    (push-key :d)
    (wait 2)
    (check (> (math.abs (- state.cam.yaw yaw)) 5)
           (string.format "a tapped key turns the camera (%.1f degrees)" (- state.cam.yaw yaw)))))

(fn check-click [{: state : wait : check}]
  "Motion with no button held, then a click and a small drag: only the drag turns
the camera."
  (let [yaw state.cam.yaw]
    (love.event.push :mousemoved 300 100 280 0 false)
    (love.event.push :mousepressed 300 100 1 false 1)
    (love.event.push :mousemoved 310 100 10 0 false)
    (love.event.push :mousereleased 310 100 1 false 1)
    (love.event.push :mousemoved 20 100 -290 0 false)
    (wait 2)
    (let [turned (- state.cam.yaw yaw)]
      (check (< (math.abs (- (math.abs turned) 2)) 1e-6)
             (string.format "only motion between press and release turns the camera (%.1f degrees; 2 expected)" turned)))))

(fn check-screenshot [{: state : wait : check}]
  "F12: the window as it looks, at window resolution, whatever the render scale
(lowered here with - twice, which check-next-scene relies on)."
  (push-key "-")
  (push-key "-")
  (wait 2)
  (set state.message nil)
  (push-key :f12)
  (wait 4)
  (let [(w h name) (string.match (or state.message "") "saved the window %((%d+)x(%d+)%) to .-/([^/]+%.png)")
        data (and name (love.filesystem.getInfo name) (love.image.newImageData name))]
    (check (and data (= (data:getWidth) (love.graphics.getWidth))
                (= (data:getHeight) (love.graphics.getHeight))
                (= (tonumber w) (love.graphics.getWidth)))
           (string.format "F12 saves the window at its own size (%s; window %dx%d, render scale %.2f)"
                          (tostring state.message) (love.graphics.getWidth) (love.graphics.getHeight)
                          state.scale))
    (when name (love.filesystem.remove name))))

(fn check-panel [{: state : wait : check}]
  "The parameter panel: F2 opens it; the radius slider dragged to a quarter (no
shader compiled, the camera still), the shadows checkbox clicked off and the tint's
green slider clicked at its end."
  (push-key :f2)
  (wait 2)
  (check state.panel.open? "F2 opens the parameter panel")
  (let [item (item-named "radius")
        compiles state.cache.compiles]
    (love.event.push :mousepressed (+ item.x (* 0.75 item.w)) (+ item.y 5) 1 false 1)
    (love.event.push :mousemoved (+ item.x (* 0.25 (- item.w 1))) (+ item.y 5) -100 0 false)
    (love.event.push :mousereleased (+ item.x (* 0.25 (- item.w 1))) (+ item.y 5) 1 false 1)
    (let [yaw state.cam.yaw]
      (wait 2)
      (let [r (. state.scene.objects 1 :radius)]
        (check (< (math.abs (- r 0.875)) 1e-9)
               (string.format "dragging the radius slider to a quarter sets 0.875 (got %s)" r))
        (check (= state.cache.compiles compiles)
               (string.format "dragging a slider compiles no shader (%d compiled)" (- state.cache.compiles compiles)))
        (check (= yaw state.cam.yaw) "dragging a slider does not turn the camera"))))
  (let [box (item-named "shadows")]
    (love.event.push :mousepressed (+ box.x 5) (+ box.y 5) 1 false 1)
    (love.event.push :mousereleased (+ box.x 5) (+ box.y 5) 1 false 1)
    (wait 2)
    (check (= false state.scene.render.shadows) "clicking the checkbox switches shadows off"))
  (let [g (item-named "tint g")]
    (love.event.push :mousepressed (+ g.x g.w -1) (+ g.y 5) 1 false 1)
    (love.event.push :mousereleased (+ g.x g.w -1) (+ g.y 5) 1 false 1)
    (wait 2)
    (check (= 1 (. state.scene.objects 1 :color 2)) "the colour's green slider at its end sets 1")))

(fn check-mesh-key [{: state : wait : check}]
  "F9: a mesh of the scene as shown (the radius dragged to 0.875; the plane left
out) beside the scene file."
  (set state.message nil)
  (push-key :f9)
  (wait 4)
  (let [formats (require :src.mesh.formats)
        check-mesh (require :src.mesh.check)
        written (string.match (or state.message "") "^wrote (.-%.ply): ")
        bytes (when written (files.read-user written))
        m (when bytes (formats.decode bytes :ply))
        v (when m (check-mesh.volume m))
        want (* (/ 4 3) math.pi (^ 0.875 3))]
    (check (and m (. (check-mesh.topology m) :manifold?) (< (math.abs (- v want)) (* 0.01 want))
                (string.find state.message "left out objects[2] (plane): infinite" 1 true))
           (string.format "F9 writes a closed mesh of the scene as shown beside it (%s; volume %s, a sphere of 0.875: %.4f)"
                          (tostring state.message) (tostring v) want))
    (when written (os.remove written))))

(fn check-save [{: state : path : wait : check &as cx}]
  "The panel's Save writes only the three changed literals into the file, which is
then reloaded as a value edit."
  (let [save (item-named "Save to file (ctrl+s)")
        reloads state.reloads]
    (love.event.push :mousepressed (+ save.x 5) (+ save.y 5) 1 false 1)
    (love.event.push :mousereleased (+ save.x 5) (+ save.y 5) 1 false 1)
    (wait 2)
    (let [expected (-> scene-text
                       (string.gsub "%(param :shadows true%)" "(param :shadows false)")
                       (string.gsub "\n                           1   " "\n                           0.875   ")
                       (string.gsub "%[0%.8 0%.3 0%.2%]" "[0.8 1 0.2]"))
          saved (files.read-user path)]
      (check (= saved expected)
             (.. "Save writes only the three literals into the file"
                 (if (= saved expected) "" (.. "; it reads:\n" (tostring saved))))))
    ;; The watcher loads a file once it has settled (0.01 s); the wait ends as soon
    ;; as it has, and its cap is generous so that a loaded CI machine cannot fail it.
    (wait-while cx #(= state.reloads reloads) 20)
    (check (and (> state.reloads reloads) (not state.last-load.compiled?) (= state.error nil))
           (string.format "the saved file is reloaded as a value edit (%d reloads, %s)"
                          (- state.reloads reloads)
                          (if (?. state.last-load :compiled?) "compiled" "uniforms only")))))

(fn check-structural-edit [{: state : path : wait : check :warm w &as cx}]
  "A structural edit with the compile helper on, as when playing: the load waits
for the helper while the last scene stays on screen, then shows the new scene, its
shader compiled once. Whether the driver's cache really fills does not matter here
(only how long the player's own compile takes)."
  (let [old state.scene
        compiles state.cache.compiles
        reloads state.reloads
        text (files.read-user path)]
    (scripted.write! path (pick-values 1 (text:gsub ":objects %[" ":objects [{:kind :box :size [1 1 1] :pos [2 0 0.5] :color [0.2 0.4 0.9]}\n")))
    (play.poll-file! (+ (filestat.now) 0.01))
    (play.poll-file! (+ (filestat.now) 0.3))
    (check (and w.enabled? state.pending (= state.scene old) (= state.cache.compiles compiles))
           (string.format "a structural edit waits for the compile helper, the last scene on screen (%s, %s)"
                          (if w.enabled? "helper found" "no helper") (tostring state.error)))
    ;; The frame drawn right after the edit (the load it waits for can end no
    ;; sooner than the next update, however quick the helper): recorded as drawn,
    ;; so the check does not race the helper.
    (let [draw love.draw
          seen []]
      (set love.draw (fn [] (draw) (table.insert seen (?. state.drawn :scene))))
      (wait 1)
      (set love.draw draw)
      (check (= (. seen 1) old) "the last scene is still drawn while the helper works"))
    ;; The cap only stops a broken helper from hanging the check: a helper takes
    ;; about a second here.
    (wait-while cx #state.pending 240)
    (wait 2)
    (check (and (not= state.scene old) (= state.drawn.scene state.scene) (= state.reloads (+ reloads 1))
                (= state.cache.compiles (+ compiles 1)) (?. state.last-load :helper?)
                (= state.error nil) (= (warm.status w (. (play.current-plan) :key)) :done))
           (string.format "then the edited scene is drawn, its shader compiled once after the helper (%s, %s)"
                          (tostring (warm.status w (?. (play.current-plan) :key)))
                          (tostring state.error)))))

(fn check-new-view [{: state : wait : check &as cx}]
  "Another view is another shader: the last image stays until its helper is done."
  (let [before state.drawn.plan.key]
    (push-key :tab)
    (wait 2)
    (check (and state.waiting-since (= state.drawn.plan.key before))
           "a new view waits for the compile helper, the last image on screen")
    (wait-while cx #state.waiting-since 240)
    (wait 2)
    (check (and (not= state.drawn.plan.key before) (= state.error nil))
           (string.format "then the new view is drawn (%s)" (tostring state.view)))))

(fn check-killed-helper [{: state : wait : check :warm w &as cx}]
  "A helper killed at work: its job fails (or is done, when the kill came too late),
the player compiles the shader itself, and the next request starts another helper."
  (let [before state.drawn.plan.key
        dir (?. w.server :dir)
        pid (case (and dir (io.open (.. dir "/pid")))
              f (let [l (f:read "*l")] (f:close) (tonumber l)))]
    (push-key :tab)
    (wait 2)
    ;; As a crash would (SDL turns SIGTERM into a quit event the helper never reads).
    (when pid (os.execute (.. "kill -9 " pid)))
    (wait-while cx #state.waiting-since 240)
    (wait 2)
    (check (and pid (not= state.drawn.plan.key before) (= state.error nil))
           (string.format "a killed helper leaves the compile to the player (pid %s, job %s, view %s)"
                          (tostring pid) (tostring (warm.status w state.drawn.plan.key))
                          (tostring state.view)))
    (push-key :tab)
    (wait 2)
    (wait-while cx #state.waiting-since 240)
    (wait 2)
    (check (and w.server (not= w.server.dir dir)
                (= (warm.status w state.drawn.plan.key) :done))
           (string.format "and the next new shader gets a new helper (%s)"
                          (tostring (warm.status w state.drawn.plan.key))))))

(fn check-folded [{: state : path : wait : check &as cx}]
  "Settled values are drawn by the shader with them as constants (folded) once the
helper has built it; a value edit goes back to the uniform shader at once,
compiling nothing. A scene tree (a torus) gives it values to fold."
  (let [text (files.read-user path)
        reloads state.reloads]
    (scripted.write! path (pick-values 1 (text:gsub ":objects %[" ":objects [{:kind :torus :radius 1 :thickness 0.2 :pos [-2 0 1]}\n")))
    (play.poll-file! (+ (filestat.now) 0.01))
    (play.poll-file! (+ (filestat.now) 0.3))
    (wait-while cx #(not (and (> state.reloads reloads) (not state.pending))) 240)
    ;; A whole picture is not drawn again while its state stays: the camera
    ;; turns (the values stay settled) so that the next pictures are drawn.
    (wait-while cx #(not (do (push-key :d) (?. state.drawn :plan :base-key))) 240)
    (wait 2)
    (let [plan (play.current-plan)]
      (check (and plan.tape (= state.drawn.plan.base-key plan.key) (= state.error nil))
             (string.format "settled values are drawn by the folded shader the helper built, once the camera turns (%s)"
                            (tostring (?. state.drawn :plan :base-key)))))
    (let [compiles state.cache.compiles
          reloads state.reloads
          text (files.read-user path)]
      (scripted.write! path (pick-values 1 (text:gsub ":radius 1 :thickness 0.2" ":radius 1.25 :thickness 0.2")))
      (play.poll-file! (+ (filestat.now) 0.01))
      (play.poll-file! (+ (filestat.now) 0.3))
      (wait 2)
      (check (and (= nil state.drawn.plan.base-key) (= state.cache.compiles compiles)
                  (= state.reloads (+ reloads 1)) (= state.drawn.scene state.scene))
             (string.format "a value edit goes back to the uniform shader at once (%s, %d compiled)"
                            (tostring state.drawn.plan.base-key) (- state.cache.compiles compiles))))))

(fn check-helper [{: state &as cx}]
  "The compile helper's steps (warm.fnl), with a helper on as when playing; it is
left off afterwards."
  (let [w (warm.new)]
    (set w.enabled? (not= nil (and w.exe w.source)))
    (set state.warm w)
    (set cx.warm w)
    (check-structural-edit cx)
    (check-new-view cx)
    (check-killed-helper cx)
    (check-folded cx)
    (set state.warm nil)))

(fn check-next-scene [{: state : path : wait : check}]
  "] opens the next bundled scene and keeps the render scale chosen with -."
  (let [scale state.scale]
    (push-key "]")
    (wait 2)
    (check (and (< scale 1) (= state.scale scale) (not= state.path path))
           (string.format "] keeps the render scale chosen with - (%.2f, was %.2f)" state.scale scale))))

(fn check-missing-scene [{: state : path : check &as cx}]
  "A scene file that is not there: the window says it cannot be read (not that it
was deleted), also after the watcher has looked at it for a while."
  (let [missing (.. path ".missing.fnl")]
    (play.load! missing true)
    (set state.message nil)
    (wait-while cx #true 1.5)
    (check (and state.error (state.error:find "cannot read the scene file" 1 true)
                (not (string.find (or state.message "") "deleted" 1 true)))
           (string.format "a missing scene says it cannot be read, not that it was deleted (%s / %s)"
                          (tostring state.error) (tostring state.message)))))

(fn script [path check]
  "The checks, one yield per frame: events pushed before a yield are handled in the
next frame. The steps run in this order, each starting where the last left the
player."
  (let [cx {:state play.state : path : check
            :wait (fn [?n] (for [_ 1 (or ?n 1)] (coroutine.yield)))}]
    (cx.wait 3)
    (check-tapped-keys cx)
    (check-click cx)
    (check-screenshot cx)
    (check-panel cx)
    (check-mesh-key cx)
    (check-save cx)
    (check-helper cx)
    (check-next-scene cx)
    (check-missing-scene cx)))

(fn run [o]
  "Start the player on a temporary scene and run the checks; quits with 0 when
every check held, else 1."
  (let [path (scripted.temp-scene-path)
        failures []
        check (fn [ok? what]
                (print (.. "input check: " what ": " (if ok? "ok" "FAILED")))
                (when (not ok?) (table.insert failures what)))]
    (scripted.write! path scene-text)
    (love.window.setMode 320 180)
    (set play.state.quiet? true)
    (play.start! {:scene path :frames 0})
    (scripted.run-per-frame!
      #(script path check)
      #(check false (.. "the check itself failed: " $))
      (fn [_]
        (os.remove path)
        (print (string.format "input checks: %d failed" (length failures)))
        (love.event.quit (if (= 0 (length failures)) 0 1))))))

{: run}

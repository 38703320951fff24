;; Interactive play: the article's fly camera on keyboard, mouse and gamepad, rendering
;; at the window's full resolution (times a render scale), with a HUD, debug views,
;; fullscreen and screenshots. Installs LÖVE callbacks when started.

;; `pairs` under another name: a loop over `pairs` by that name is LuaJIT's ITERN,
;; which Debian 12's LuaJIT ends early once despecialised (see src/util/wire.fnl).
(local each-pair pairs)

(local camera (require :src.render.camera))
(local frame (require :src.backend.frame))
(local scene-mod (require :src.scene.load))
(local worker (require :src.scene.worker))
(local adaptive (require :src.app.adaptive))
(local quality (require :src.app.quality))
(local hud (require :src.app.hud))
(local {: median} (require :src.util.stats))
(local gpu (require :src.backend.gpu))
(local plan-mod (require :src.render.plan))
(local watch (require :src.app.watch))
(local filestat (require :src.util.filestat))
(local output (require :src.util.output))
(local progress (require :src.app.progress))
(local text (require :src.util.text))
(local params (require :src.scene.params))
(local panel (require :src.app.panel))
(local warm (require :src.app.warm))
(local preview (require :src.app.preview))
(local codegen (require :src.render.codegen))
(local uniforms (require :src.render.uniforms))

(local move-speed 10)   ; world units per second
(local turn-speed 90)   ; degrees per second
(local fov-speed 30)    ; degrees per second
(local mouse-degrees-per-pixel 0.2)
(local dead-zone 0.2)   ; the article's gamepad dead zone

(local state {:scene nil :path nil :cam nil :view :shaded :reflections 0
              :scale 1 :hud? true :cache nil :canvas nil :message nil :taps {} :dragging? false
              :time 0 :paused? false :adaptive (adaptive.new) :move-canvas nil
              :move-times []
              ;; One scene state a picture: `generation` counts the changes of the
              ;; scene's values (a load, a slider, the clock), `picture` is what is on
              ;; screen ({: key : canvas}, key from state-key), `refine` the full
              ;; resolution being drawn in bands for that same key, and `last-render`
              ;; the render of the last frame, timed for the frame-time model.
              :generation 0 :plan-id 0 :picture nil :refine nil :last-render nil
              :first-picture nil
              :messages [] :error nil :gamepad nil :watch nil :poll-at 0
              :reloads 0
              ;; Compiles in a helper process first (warm.fnl; nil: in the player), the
              ;; load waiting for its helper ({: path : fresh? : key : start}) and the
              ;; last scene and plan drawn ({: scene : plan}), shown meanwhile.
              :warm nil :pending nil :drawn nil :waiting-since nil
              ;; While a state waits for its helper's shader, the CPU reference's
              ;; pictures of it (preview.fnl): the previewer, the request in force
              ;; ({: id : key : cam-key : since : cam : options}), the last preview
              ;; drawn ({: id : image : w : h : at : first}) and this frame's (or nil).
              :preview nil :preview-request nil :previewed nil :shown-preview nil
              ;; On a GPU the tape interpreter (src/sdf/interpret.fnl) draws a
              ;; structural edit at once, while the helper compiles its shader:
              ;; whether this player does (interpret-edits?), and the key of the
              ;; shader awaited while it draws (interpreting).
              :interpret-edits? false :interpreting nil
              ;; How many times a load ran the scene file (in the worker).
              :scene-runs 0
              ;; When the helper was last asked for the interpreter's shader (see
              ;; warm-interpreter-when-idle!).
              :interpreter-asked nil
              ;; Before the first picture: the file being opened ({: path : start})
              ;; and when the opening screen was last drawn (see show-opening!).
              :opening nil :opening-shown 0
              ;; The parameter panel: open?, the slider being dragged, and the values
              ;; moved away from the file's, by name ({:value :base}, see params).
              :panel {:open? false :drag nil :overrides {} :status ""}})

(fn scenes-in-folder []
  (let [items (love.filesystem.getDirectoryItems "scenes")]
    (table.sort items)
    (icollect [_ name (ipairs items)]
      (when (name:match "%.fnl$") (.. "scenes/" name)))))

(fn say! [message ?seconds]
  "Show `message` in the HUD for `?seconds` (4), under the ones still showing (the
last four are kept), and print it."
  (let [message (text.printable message)]
    (when (not state.quiet?) (print message))
    (set state.message message)
    (table.insert state.messages {:text message
                                  :until (+ (love.timer.getTime) (or ?seconds 4))})
    (when (> (length state.messages) 4) (table.remove state.messages 1))))

(fn show-opening! [step ?force?]
  "While a scene is opened and nothing is on screen yet, what is being done (`step`)
and for how long, on a plain screen drawn and shown at once: a heavy scene's first
load, lowering and compile take seconds, and the window would stay black. At most
ten times a second unless `?force?` (a new step)."
  (let [now (love.timer.getTime)
        o state.opening]
    (when (and o (= nil state.picture) (love.graphics.isActive)
               (or ?force? (> (- now state.opening-shown) 0.1)))
      (set state.opening-shown now)
      (love.graphics.origin)
      (love.graphics.clear 0.1 0.1 0.12 1)
      (love.graphics.setColor 1 1 1 1)
      (love.graphics.printf (text.printable (string.format "opening %s\n%s (%.1f s)" o.path step
                                                           (- now o.start)))
                            16 16 (math.max 64 (- (love.graphics.getWidth) 32)))
      (love.graphics.present))))

(fn changed! []
  "The scene's values changed: a picture of the old ones is of another state."
  (set state.generation (+ state.generation 1)))

;;; Loading and hot reload

;; With RAYMARCH_FRAME_LOG (see log-frame!): each loaded scene's text, and a serial
;; number for each text drawn.
(local frame-log-path (case (os.getenv "RAYMARCH_FRAME_LOG") "" nil path path))
(local scene-texts (setmetatable {} {:__mode :k}))
(local frame-serials {})

(fn file-info [path]
  "The watched file's modification time, size and text; {:problem why} when it is
there but cannot be read; nil when it is missing. The text is read before the time,
so a write during the read shows as a newer time (see watch.poll!). Files found only
inside the game folder (LÖVE run from elsewhere) have whole-second times."
  (let [content (frame.read-text path)
        st (filestat.stat path)]
    (if st
        (if (= st.kind :directory) {:problem "it is a directory"}
            (or (not st.readable?) (not content)) {:problem "it cannot be read"}
            {:mtime st.mtime :coarse? st.coarse? :size st.size : content})
        (let [i (love.filesystem.getInfo path :file)]
          (when (and i content) {:mtime i.modtime :coarse? true :size i.size : content})))))

(fn same-camera? [a b]
  (and a b (= a.yaw b.yaw) (= a.pitch b.pitch) (= a.fov b.fov)
       (= (. a.pos 1) (. b.pos 1)) (= (. a.pos 2) (. b.pos 2)) (= (. a.pos 3) (. b.pos 3))))

;; The still: once the full-resolution picture of a state is whole and the state
;; stays, it is drawn again over itself, band by band, with adaptive supersampling
;; (shaders/pipeline/adaptive.glsl: still-samples x still-samples rays where the
;; centre ray finds an edge or a second ray disagrees): the same state, anti-aliased,
;; without the dotted edges and sparkles of one ray per pixel.
;; `love . --render` and --record draw the same still by default (src/app/quality.fnl).
(local still-samples quality.still-samples)

(fn plan-options [reflections]
  ;; The player's plan options (the view, the reflection count, the model), as a
  ;; plan and a preview take them.
  {:view state.view : reflections :model (when state.classic? :classic)})

(var catalogue nil)

(fn plan-with [scene reflections ?fold? ?still? ?interpret?]
  ;; With `?interpret?`, the tape interpreter's plan, holding every kind (the
  ;; catalogue): one shader for the scene and its edits.
  (when (and ?interpret? (not catalogue))
    (set catalogue ((. (require :src.sdf.interpret) :catalogue))))
  (let [still (when ?still? (quality.still-options))]
    (frame.plan-for scene (doto (plan-options reflections)
                            (tset :fold? ?fold?)
                            (tset :samples (?. still :samples))
                            (tset :adaptive? (?. still :adaptive?))
                            (tset :interpret? ?interpret?)
                            (tset :instructions (when ?interpret? catalogue))))))

(fn interpreter-plan [scene reflections]
  "The interpreter's plan of `scene`, when this player draws edits with it and the
scene can run on it; else nil."
  ;; (A scene of more objects than it runs is not lowered again to hear so.)
  (when (and state.interpret-edits? (plan-mod.interpreter-count-fits? scene))
    (pick-values 1 (plan-with scene reflections nil nil true))))

(fn interpreter-ready [scene reflections]
  "The interpreter's plan of `scene` when its shader can be drawn now (compiled here,
or built by the helper: the player's compile is then a hit in the driver's cache);
else nil."
  (case (interpreter-plan scene reflections)
    iplan (when (or (gpu.cached? state.cache iplan)
                    (= :done (?. state.warm :settled iplan.key)))
            iplan)))

(fn warm-source [scene plan]
  ;; What the compile helper gets: the shader's text, after a line for each texture
  ;; the player will bind with its size (see warm-helper.fnl).
  (case (codegen.shader plan :love)
    source (.. (table.concat
                 (icollect [_ u (ipairs (uniforms.pack scene plan state.cam 8 8))]
                   (when (= u.type :texture)
                     (string.format "//warm-texture %s %d %d\n" u.name u.texture.width
                                    u.texture.height))))
               source)
    (nil err) (values nil err)))

(fn compile-waits? [scene plan]
  "True while the shader of `plan` (for `scene`) is being compiled by a helper process
(warm.fnl): the player goes on drawing what it drew last. Never when nothing is on
screen yet, or when the shader is compiled already."
  (and state.warm state.drawn (not (gpu.cached? state.cache plan))
       (not (warm.ready? state.warm plan.key #(warm-source scene plan)))))

;; A new shader's first renders: one pixel (the driver builds its code at the first
;; draw), then two sizes timed, small enough for any scene (colonnade, about 11 us a
;; pixel on llvmpipe, takes 30 ms for both) and apart enough to fit a line.
(local probe-sizes [[1 1] [16 9] [64 36]])

(fn warm-interpreter! [scene reflections]
  "Have the helper build the interpreter's shader for `scene`'s plan in the background,
unless it is built: the next structural edit is then drawn with it at once."
  (case (interpreter-plan scene reflections)
    iplan (when (and (?. state.warm :enabled?) (not (gpu.cached? state.cache iplan)))
            (warm.ready? state.warm iplan.key #(warm-source scene iplan) true))))

(fn probe! [scene plan]
  "Draw `plan`'s shader into small canvases, timed: the driver builds the code it runs
(at its first draw), and the frame-time model learns what a picture costs, so the
first picture of the scene can be sized to come at once."
  (each [i [w h] (ipairs probe-sizes)]
    (let [canvas (love.graphics.newCanvas w h)
          start (love.timer.getTime)]
      (frame.render-to-canvas! state.cache canvas scene plan state.cam)
      (let [data (canvas:newImageData 1 1 0 0 1 1)] (data:release))
      (when (> i 1)
        (adaptive.rendered! state.adaptive plan.key (* w h) (- (love.timer.getTime) start)))
      (canvas:release))))

;; The collector after a load. LuaJIT starts a cycle once the heap has doubled since
;; the last one ended (a pause of 200%), and a cycle does twice the work of what is
;; allocated meanwhile (a step multiplier of 200%): with a million spheres' scene
;; live (800 MB), the idle player's garbage (0.7 MB a second: the HUD's text, the
;; frame's tables) grew the process by 800 MB before a cycle started, and 400 MB
;; more before it ended. A large heap is collected once the scene is in, the next
;; cycle starts after collector-slack more and ends within a tenth of the heap's
;; size (large-stepmul); a load goes back to the defaults (its allocations, a GB for
;; those spheres, would otherwise run cycle after cycle over what lives).
(local collector-large (* 256 1024))   ; KB of heap
(local collector-slack (* 128 1024))   ; KB of garbage between cycles, at least
(local default-pause 200)
(local default-stepmul 200)
(local large-stepmul 1000)

(fn default-collector! []
  (collectgarbage :setpause default-pause)
  (collectgarbage :setstepmul default-stepmul))

(fn pause-for [heap]
  ;; The collector's pause (percent) that starts a cycle after collector-slack more
  ;; than `heap` KB.
  (math.floor (math.min default-pause (* 100 (/ (+ heap collector-slack) heap)))))

(fn settle-collector! []
  ;; A cycle's end sets the next one's start from the pause it finds (lj_gc), so the
  ;; pause goes first: taken from the heap before the collection (garbage and all,
  ;; so a little less slack), then from what lives, for the cycles after.
  (let [heap (collectgarbage :count)]
    (if (> heap collector-large)
        (do (collectgarbage :setpause (pause-for heap))
            (collectgarbage :setstepmul large-stepmul)
            (collectgarbage)
            (collectgarbage :setpause (pause-for (collectgarbage :count))))
        (default-collector!))))

(fn camera-after-load [scene old fresh?]
  "The camera once `scene` is loaded over `old` (nil: none; `fresh?`: a new file): the
file's own for a new file, or when the file's camera changed and the player has not
moved it since; else the player's."
  (let [file-cam (camera.from-scene scene)
        user-moved? (and old state.cam (not (same-camera? state.cam (camera.from-scene old))))]
    (if (or fresh? (not state.cam)
            (and (not user-moved?) (not (same-camera? file-cam (camera.from-scene old)))))
        file-cam
        state.cam)))

(fn request-preview! [scene reflections cam key since]
  "Ask the preview thread for pictures of `scene` (whose shader `key` a helper
compiles: a load's, or a view's or a switch's), seen by `cam`, as the player's plan
options draw it; `since`: when the change was asked for."
  (let [(ww wh) (love.graphics.getDimensions)
        options (plan-options reflections)]
    (case (preview.request! state.preview scene options cam (/ ww wh))
      id (set state.preview-request {: id : key :cam-key (adaptive.camera-key state.cam)
                                     : since : cam : options})
      (nil why) (do (set state.preview-request nil)
                    (when (not state.quiet?) (io.stderr:write (.. "no preview: " why "\n")))))))

(fn load-unprotected! [path fresh? ?since ?now ?pending]
  "Load the scene at `path` and switch to it once its shader is ready. `fresh?` (a new
file, not an edit) resets the camera and the player's settings; an edit keeps them,
unless the file's own camera or settings changed and the player left them alone.
On any failure the last good scene keeps running and the error is shown, unless the
read may have caught the file mid-write (watch.failure-stands?, judged at `?now`,
the wall clock): then nothing is said and the watcher loads it again once it has
stayed the same for a moment (watch.retry!). A shader that a helper process is
compiling leaves the load pending (state.pending); update loads the file again once
the helper is done, `?since` the time of the first try, `?pending` that load: its
scene is taken again when the file still holds its text and no value changed since
(the scene file is not run again: 50-100 ms of the worker's)."
  (set state.retry-fresh? nil)
  ;; The collector's defaults while loading (see settle-collector!).
  (default-collector!)
  (let [start (or ?since (love.timer.getTime))
        _ (set state.opening {: path : start})
        info (file-info path)
        old state.scene
        ;; Slider positions not yet saved survive an edit of the file (params drops
        ;; one whose literal the edit changed); a new file starts from its own values.
        _ (when fresh? (set state.panel.overrides {}))
        (scene err) (if (and ?pending (= ?pending.generation state.generation)
                             (= ?pending.text (?. info :content)))
                        ?pending.scene
                        (do (set state.scene-runs (+ state.scene-runs 1))
                            (frame.load-scene path {:overrides state.panel.overrides})))]
    (when (and scene frame-log-path) (tset scene-texts scene (?. info :content)))
    (when (or fresh? (not state.watch))
      (set state.watch (watch.new info)))
    (watch.loaded! state.watch info)
    (if (and (not scene)
             (not (watch.failure-stands? info (file-info path) (or ?now (filestat.now)))))
        ;; Caught mid-write, perhaps: no error yet; the watcher loads it again.
        (do (watch.retry! state.watch)
            (set state.retry-fresh? fresh?)
            (when fresh? (set state.path path)))
        (not scene)
        (do (set state.error err)
            (when fresh? (set state.path path))
            (when (not state.quiet?) (io.stderr:write (.. err "\n"))))
        (let [file-changed? (fn [get] (or fresh? (not old) (not= (get scene) (get old))))
              reflections (if (file-changed? #$.render.reflections)
                              scene.render.reflections
                              state.reflections)
              _ (show-opening! (string.format "%d objects read; lowering them into the shader's tape"
                                              (length scene.objects))
                               true)
              (plan perr) (plan-with scene reflections)
              _ (when plan (show-opening! "generating and compiling the shader" true))
              wait? (and plan (compile-waits? scene plan))
              ;; An edit whose shader the helper compiles is drawn by the tape
              ;; interpreter meanwhile, when its shader is ready; the load stays
              ;; pending and runs again when the helper is done.
              interp (when (and wait? old (not fresh?)) (interpreter-ready scene reflections))
              drawn-plan (or interp plan)
              compiles-before state.cache.compiles
              (shader serr) (if (and wait? (not interp)) (values nil nil)
                                plan (gpu.shader-for state.cache drawn-plan)
                                (values nil perr))]
          (if (and wait? (not interp))
              (do (when (not= (?. state.pending :key) plan.key)
                    (say! (.. path ": compiling its shader in a helper process; "
                              (if old "a preview by the CPU reference meanwhile" "please wait"))))
                  ;; Over a scene on screen: its pictures by the CPU reference until
                  ;; the shader is ready.
                  (when (and state.preview old (not= (?. state.preview-request :key) plan.key))
                    (request-preview! scene reflections (camera-after-load scene old fresh?) plan.key
                                      start))
                  (set state.pending {: path : fresh? :key plan.key : start : scene : plan
                                      :generation state.generation :text (?. info :content)}))
              (not shader)
              (do (set state.error serr)
                  (when (not state.quiet?) (io.stderr:write (.. serr "\n"))))
              (do
                (set state.cam (camera-after-load scene old fresh?))
                ;; A render scale chosen with - and = stays when [ and ] open another
                ;; scene (on a slow machine, 1 would mean a few frames a second).
                (when (and (file-changed? #$.render.scale) (not (and fresh? old state.user-scale?)))
                  (set state.scale scene.render.scale))
                (set state.reflections reflections)
                ;; A new file starts its functions of time at 0; an edit keeps the clock.
                (if fresh? (set state.time 0)
                    (scene-mod.animated? scene) (worker.animate scene state.time))
                (set state.scene scene)
                (set state.interpreting (when interp plan.key))
                (changed!)
                (set state.path path)
                (set state.error nil)
                (set state.reloads (+ state.reloads 1))
                ;; A new shader is ready once the driver has also built the code it
                ;; runs, at its first draw: that is part of the compile, not of the
                ;; first picture.
                (when (> state.cache.compiles compiles-before)
                  (show-opening! "the driver builds the shader's code at its first draw" true)
                  (probe! scene drawn-plan))
                (set state.first-picture {:since (love.timer.getTime) : path})
                (let [ms (* 1000 (- (love.timer.getTime) start))
                      compiled? (> state.cache.compiles compiles-before)]
                  (set state.last-load {:ms ms :compiled? compiled? :helper? (not= ?since nil)
                                        :interpreted? (not= nil interp)})
                  (say! (string.format "%s %s in %.0f ms (%s)" (if fresh? "loaded" "reloaded")
                                       path ms (if interp "drawn by the tape interpreter while a helper compiles its shader"
                                                   (not compiled?) "uniforms only"
                                                   ?since "shader compiled by a helper process"
                                                   "shader compiled")))
                  ;; The helper's shader replaces the interpreter's when it is done.
                  (when interp
                    (set state.pending {: path : fresh? :key plan.key : start : scene : plan
                                        :generation state.generation :text (?. info :content)}))
                  (settle-collector!))))))))

(fn load! [path fresh? ?since ?now ?pending]
  "Load the scene at `path` (see load-unprotected!); a failure inside the loader
itself is shown like a broken file, and the last good scene keeps running."
  ;; A newer load replaces the one waiting for its helper, and values asked for the
  ;; scene before it.
  (set state.pending nil)
  (set state.time-pending nil)
  (when state.preview
    (preview.cancel! state.preview)
    (set state.preview-request nil))
  (let [(ok? err) (xpcall load-unprotected! debug.traceback path fresh? ?since ?now ?pending)]
    (when (not ok?)
      (set state.error (.. path ": the scene could not be loaded (an internal error): "
                           (tostring err))))))

(fn finish-pending! []
  "Collect finished helpers; a load waiting for one that is done runs again (now a
cache hit in the driver, or a plain compile when the helper failed)."
  (when state.warm
    (warm.poll! state.warm)
    (when (and state.warm.gave-up? (not state.warm.said?))
      (set state.warm.said? true)
      (say! "the compile helper failed three times in a row: shaders compile in the player from now on"))
    (case state.pending
      ;; A load whose job is no longer asked for (a newer request of the edit lane,
      ;; a new view, replaced it while it waited) asks again. Before issue 42 a
      ;; background request could replace it, and the edit never showed.
      p (if (warm.settled? state.warm p.key)
            (load! p.path p.fresh? p.start nil p)
            (= nil (warm.status state.warm p.key))
            (when (warm.ready? state.warm p.key #(warm-source p.scene p.plan))
              (load! p.path p.fresh? p.start nil p))))))

(fn apply-parameters! []
  "The panel moved a value: evaluate the scene's text again with the panel's values
(a value edit compiles nothing; a switch that changes the shader compiles it once)."
  (let [(scene err) (worker.load-source state.scene.source state.path
                                         {:overrides state.panel.overrides})]
    (set state.time-pending nil)
    (if (not scene)
        (set state.error err)
        (do (when (scene-mod.animated? scene) (worker.animate scene state.time))
            (set state.scene scene)
            (changed!)
            (set state.error nil)))))

(fn parameter-status []
  (let [changed (accumulate [n 0 _ p (ipairs (or (?. state.scene :params) []))]
                  (if (params.same-value? p.value p.default) n (+ n 1)))]
    (if (> changed 0) (.. changed " unsaved") state.panel.status)))

(fn save-parameters! []
  "Write the panel's values into the scene file (only those literals change); the
file watcher then reloads it as a value edit."
  (when (?. state.scene :params)
    (case (params.save! state.path state.scene.params)
      (nil err) (do (set state.panel.status "not saved") (say! err))
      n (do (set state.panel.overrides {})
            (set state.panel.status "saved")
            (say! (string.format "saved %d value%s to %s" n (if (= n 1) "" "s") state.path))))))

(fn set-parameter! [p v]
  (tset state.panel.overrides p.name {:value v :base p.default})
  (set state.panel.status "")
  (apply-parameters!))

(fn reset-parameters! []
  (set state.panel.overrides {})
  (set state.panel.status "")
  (apply-parameters!))

(fn toggle-panel! []
  (if (?. state.scene :params)
      (set state.panel.open? (not state.panel.open?))
      (say! "this scene has no parameters: mark a value in the file with (param :name value {:min A :max B})")))

(fn panel-layout []
  (when (and state.panel.open? (?. state.scene :params))
    (panel.layout state.scene.params (love.graphics.getWidth))))

(local poll-seconds 0.01)   ; with watch.settle-seconds, an edit is read 10-20 ms after its save

(fn polled-info [path]
  "file-info for the watcher, which looks a hundred times a second: the file is read
again only when its stat says it may have changed (watch.read-again?)."
  (let [st (filestat.stat path)
        last state.polled]
    (if (not (watch.read-again? last st))
        last.info
        (let [read-at (filestat.now)
              info (file-info path)]
          (set state.polled (when (and st info (not info.problem))
                              {:mtime st.mtime :size st.size :ino st.ino :dev st.dev
                               : read-at : info}))
          info))))

(fn poll-file! [?now]
  "Look at the watched file, poll-seconds apart at most (a stat; the file is read
only when that changed: polled-info). `?now` overrides the wall clock (the soak test
moves it forward instead of waiting)."
  (let [clock (filestat.now)]
    ;; While another file's load waits for its helper, state.watch is that file's.
    (when (and state.path state.watch (not (?. state.pending :fresh?))
               (or ?now (>= clock state.poll-at)))
      (set state.poll-at (+ clock poll-seconds))
      (let [info (polled-info state.path)]
        (case (watch.poll! state.watch info (or ?now (filestat.now)))
          ;; A retry of a new file that was caught mid-write is still a new file.
          :changed (load! state.path (= true state.retry-fresh?) nil ?now)
          ;; A file missing from the start was never there to be deleted: the load
          ;; error on screen says so already.
          :deleted (when state.watch.loaded
                     (say! (.. state.path " was deleted"
                               (if state.scene "; the last good scene keeps running" ""))))
          :unreadable (say! (.. state.path ": " (or state.watch.problem "it cannot be read")
                                "; the last good scene keeps running")))))))

(fn pause-clock! [err]
  (set state.time-pending nil)
  (set state.error (.. err " (the animation is paused; space plays)"))
  (when (not state.quiet?) (io.stderr:write (.. state.error "\n")))
  (set state.paused? true))

(fn take-values! [wait]
  ;; The values asked for at state.time-pending, when the worker has them (waiting
  ;; at most `wait` seconds; frames go on meanwhile).
  (case (worker.poll-animate! state.scene wait)
    :pending nil
    true (do (set state.time state.time-pending)
             (set state.time-pending nil)
             (set state.plan-memo nil)
             (changed!))
    (nil err) (pause-clock! err)))

(fn advance-time! [dt]
  "Functions of time in the scene: move the clock (unless paused) and set their values
for it; the plan is lowered again (values only: no shader compile). The values come
from the scene worker: asked for, then taken when they arrive (within the frame, or
a later one: the clock waits for them meanwhile and the player stays responsive). A
failing function (or functions past their budget for a frame, or a worker stopped
past its deadline) shows its message, keeps the last values and pauses the clock
(space tries again)."
  (when (and state.scene (scene-mod.animated? state.scene))
    (if state.time-pending
        (take-values! 0)
        (or (not state.paused?) state.step?)
        (let [t (+ state.time (if state.step? (/ 1 30) dt))]
          (set state.step? false)
          (case (worker.request-animate! state.scene t)
            true (do (set state.time-pending t) (take-values! 0.02))
            (nil err) (pause-clock! err))))))

(fn current-plan []
  "The plan of the scene on screen, lowered again only when the scene, the view or
the reflection count changed (not every frame)."
  (let [memo state.plan-memo]
    (if (and memo (= memo.scene state.scene) (= memo.view state.view)
             (= memo.reflections state.reflections) (= memo.classic? state.classic?)
             (= memo.interpreting state.interpreting))
        (values memo.plan memo.err)
        (let [(plan err) (plan-with state.scene state.reflections nil nil
                                    (not= nil state.interpreting))]
          ;; New values (an edit, a slider, the clock): the uniform shader draws them
          ;; at once; the folded one waits until they settle (see folded-plan).
          (set state.plan-id (+ state.plan-id 1))
          (set state.plan-memo {:scene state.scene :view state.view :classic? state.classic?
                                :reflections state.reflections : plan : err
                                :interpreting state.interpreting
                                :since (love.timer.getTime) :id state.plan-id})
          (values plan err)))))

;; Values unchanged this long have settled: the compile helper then builds the shader
;; with them as constants (plan option :fold?, 1.08-1.13x faster on llvmpipe), and
;; the player draws with it once it is ready. A value edit goes back to the uniform
;; shader at once (a new plan); functions of time keep their values uniforms while
;; the clock runs.
(local fold-after 0.5)

(fn folded-plan [plan]
  "The folded twin of `plan`, the plan on screen, once its values have settled and
its shader is ready (compiled, or done by the helper); else nil, asking the helper
for it. Never without the helper (a compile would freeze the window), nor for a
plan without scene trees (nothing to fold)."
  (let [memo state.plan-memo
        scene state.scene]
    (when (and plan.tape state.warm state.warm.enabled? memo (= memo.plan plan)
               (not state.interpreting)
               (not (and (scene-mod.animated? scene) (not state.paused?)))
               (>= (- (love.timer.getTime) memo.since) fold-after))
      (when (= nil memo.folded)
        (let [(folded) (plan-with scene state.reflections true)]
          (when folded (set folded.base-key plan.key))
          (set memo.folded (or folded false))))
      (let [folded memo.folded]
        (when (and folded (or (gpu.cached? state.cache folded)
                              ;; Not while a load waits for its shader: the edit
                              ;; lane first.
                              (and (not state.pending) (not state.waiting-since)
                                   (warm.ready? state.warm folded.key
                                                #(warm-source scene folded) true)
                                   ;; A failed helper leaves no folded shader: a
                                   ;; compile here would freeze the window.
                                   (not= :failed (warm.status state.warm folded.key)))))
          folded)))))

;; While the state changes the image is drawn whole at a lower resolution, chosen to
;; hold this frame rate; when it stays, the full resolution is refined in bands.
(local default-interactive-fps 30)

(fn ensure-move-canvas! [s]
  (let [(ww wh) (love.graphics.getDimensions)
        w (math.max 1 (math.floor (* ww s)))
        h (math.max 1 (math.floor (* wh s)))]
    (when (or (not state.move-canvas)
              (not= w (state.move-canvas:getWidth)) (not= h (state.move-canvas:getHeight)))
      (when state.move-canvas (state.move-canvas:release))
      (set state.move-canvas (love.graphics.newCanvas w h))
      (state.move-canvas:setFilter :linear :linear))
    state.move-canvas))

(fn ensure-canvas! []
  (let [(ww wh) (love.graphics.getDimensions)
        w (math.max 1 (math.floor (* ww state.scale)))
        h (math.max 1 (math.floor (* wh state.scale)))]
    (when (or (not state.canvas)
              (not= w (state.canvas:getWidth)) (not= h (state.canvas:getHeight)))
      (when state.canvas (state.canvas:release))
      (set state.canvas (love.graphics.newCanvas w h))
      (state.canvas:setFilter :nearest :nearest))
    state.canvas))

;;; Input

(fn down? [...] (love.keyboard.isDown ...))

;; At a frame a second a short tap is pressed and released between two updates, so
;; love.keyboard.isDown never sees it: a press counts as held for at least this long.
(local tap-seconds 0.15)

(fn held [key dt]
  "Seconds `key` counts as held this update: the frame time while it is down, and at
least tap-seconds for a key pressed since the last update."
  (let [tapped? (. state.taps key)]
    (if (down? key) (if tapped? (math.max dt tap-seconds) dt)
        tapped? tap-seconds
        0)))

(fn modifier-down? []
  ;; ctrl+s saves, alt+return goes fullscreen: keys held with these move nothing.
  (down? :lctrl :rctrl :lalt :ralt :lgui :rgui))

(fn move-by-keys! [dt]
  (let [cam state.cam
        shift? (down? :lshift :rshift)
        w (held :w dt) s (held :s dt) a (held :a dt) d (held :d dt)]
    (when (> (+ w s) 0) (camera.move-forward! cam (* move-speed (- w s))))
    (when (> (+ a d) 0)
      (if shift? (camera.strafe! cam (* move-speed (- d a))) (camera.turn! cam (* turn-speed (- d a)))))
    (let [q (held :q dt) e (held :e dt)]
      (when (> (+ q e) 0) (camera.pitch! cam (* turn-speed (- q e)))))
    (let [r (held :r dt) f (held :f dt)]
      (when (> (+ r f) 0) (camera.elevate! cam (* move-speed (- r f)))))
    (let [o (held :o dt) p (held :p dt)]
      (when (> (+ o p) 0) (camera.zoom! cam (* fov-speed (- p o)))))))

(fn handle-keyboard [dt]
  (when (not (modifier-down?))
    (move-by-keys! dt))
  (set state.taps {}))

(fn axis [pad name]
  (let [v (pad:getGamepadAxis name)]
    (if (> (math.abs v) dead-zone) v 0)))

(fn handle-gamepad [dt]
  (let [pad state.gamepad
        cam state.cam]
    (when (and pad (pad:isConnected))
      (camera.move-forward! cam (* (- (axis pad :lefty)) 2 move-speed dt))
      (camera.strafe! cam (* (axis pad :leftx) move-speed dt))
      (camera.turn! cam (* (axis pad :rightx) turn-speed dt))
      (camera.pitch! cam (* (axis pad :righty) turn-speed dt))
      ;; Triggers rest at 0 in LÖVE's gamepad mapping and go to 1 when pressed.
      (camera.elevate! cam (* (- (pad:getGamepadAxis :triggerright)
                                 (pad:getGamepadAxis :triggerleft))
                              move-speed dt))
      (when (pad:isGamepadDown :dpup) (camera.zoom! cam (* (- fov-speed) dt)))
      (when (pad:isGamepadDown :dpdown) (camera.zoom! cam (* fov-speed dt))))))

(fn change-reflections! [delta]
  (set state.reflections (math.max 0 (math.min 16 (+ state.reflections delta))))
  (say! (.. "reflections: " state.reflections)))

(fn change-scale! [factor]
  (set state.scale (math.max 0.1 (math.min 1 (* state.scale factor))))
  (set state.user-scale? true)
  (say! (string.format "render scale: %.2f" state.scale)))

(fn toggle-model! []
  (if (and state.scene state.scene.lighting)
      (do (set state.classic? (not state.classic?))
          (say! (if state.classic? "lighting: the article's classic model (m: modern)"
                    "lighting: modern (m: classic)")))
      (say! "lighting: this scene has no :lighting section, so only the classic model")))

(fn cycle-view! []
  (let [views plan-mod.views]
    (var next-view (. views 1))
    (each [i v (ipairs views)]
      (when (= v state.view) (set next-view (or (. views (+ i 1)) (. views 1)))))
    (set state.view next-view)
    (say! (.. "view: " next-view))))

(fn cycle-scene! [delta]
  (let [paths (scenes-in-folder)]
    (var at 0)
    (each [i p (ipairs paths)] (when (= p state.path) (set at i)))
    (let [n (length paths)]
      (when (> n 0)
        (load! (. paths (+ (% (+ at -1 delta) n) 1)) true)))))

(fn toggle-fullscreen! []
  (love.window.setFullscreen (not (love.window.getFullscreen)) :desktop))

;; Long enough to read (or copy) the path, which the other messages do not push out.
(local screenshot-seconds 10)

(fn screenshot! [bare?]
  "F12: the window as it looks (window resolution, HUD and messages included);
shift+F12: the bare render at render resolution. Saved in LÖVE's save folder."
  (let [stamp (os.date "%Y%m%d-%H%M%S")
        name (.. (if bare? "render-" "screenshot-") stamp ".png")
        where (.. (love.filesystem.getSaveDirectory) "/" name)]
    (if bare?
        ;; The picture on screen, at its own resolution (a low one while it changes).
        (case state.picture
          {: canvas} (let [data (canvas:newImageData)]
                       (data:encode :png name)
                       (data:release)
                       (say! (string.format "saved the bare render (%dx%d) to %s"
                                            (canvas:getWidth) (canvas:getHeight) where)
                             screenshot-seconds)))
        (love.graphics.captureScreenshot
          (fn [data]
            (data:encode :png name)
            (say! (string.format "saved the window (%dx%d) to %s; shift+F12 saves the bare render"
                                 (data:getWidth) (data:getHeight) where)
                  screenshot-seconds))))))

(fn ask-mesh! []
  "F9: mesh the scene as shown. The window shows the message for two frames first:
the meshing holds the window (organic at 128 cells: about a second on llvmpipe)."
  (when state.scene
    (set state.mesh-wait 2)
    (say! "meshing the scene as shown (128 cells along its longest side) ...")))

(fn mesh-pending! []
  (when state.mesh-wait
    (set state.mesh-wait (- state.mesh-wait 1))
    (when (<= state.mesh-wait 0)
      (set state.mesh-wait nil)
      (case (when state.scene
              ((. (require :src.app.mesh) :export-shown) state.scene state.path))
        (true line) (say! line screenshot-seconds)
        (nil err) (say! (.. "mesh: " (tostring err)) screenshot-seconds)))))

(fn keypressed [key]
  (let [alt? (down? :lalt :ralt)
        ctrl? (down? :lctrl :rctrl)]
    (when (not (modifier-down?)) (tset state.taps key true))
    (case key
      :f2 (toggle-panel!)
      (where :s ctrl?) (save-parameters!)
      :escape (do (worker.kill!) (love.event.quit 0))
      :tab (cycle-view!)
      :m (toggle-model!)
      :h (set state.hud? (not state.hud?))
      :f1 (set state.hud? (not state.hud?))
      :f11 (toggle-fullscreen!)
      :return (when alt? (toggle-fullscreen!))
      :f12 (screenshot! (down? :lshift :rshift))
      :f9 (ask-mesh!)
      :f5 (load! state.path false)
      :k (change-reflections! -1)
      :l (change-reflections! 1)
      "-" (change-scale! 0.8)
      "=" (change-scale! 1.25)
      :space (do (set state.paused? (not state.paused?))
                 (say! (if state.paused? "paused (. steps a frame)" "playing")))
      "." (when state.paused? (set state.step? true))
      "[" (cycle-scene! -1)
      "]" (cycle-scene! 1))))

(fn gamepadpressed [pad button]
  (set state.gamepad pad)
  (case button
    :leftshoulder (change-reflections! -1)
    :rightshoulder (change-reflections! 1)
    :back (cycle-view!)))

;; A drag is motion between a press and its release, in event order: motion queued
;; before a click (a slow frame) must not turn the camera, as isDown would make it.
(fn press-panel! [item x]
  (case item.kind
    :slider (do (set state.panel.drag item)
                (set-parameter! item.param (panel.with-value item (panel.slider-value item x))))
    :checkbox (set-parameter! item.param (not item.param.value))
    :save (save-parameters!)
    :reset (reset-parameters!)))

(fn mousepressed [x y button]
  ;; A press on the panel works the panel and never turns the camera.
  (case (and (= button 1) (let [lay (panel-layout)] (and lay (panel.hit lay x y))))
    :panel nil
    item (press-panel! item x)
    _ (when (or (= button 1) (= button 2)) (set state.dragging? true))))

(fn mousereleased []
  (set state.panel.drag nil)
  (when (not (or (love.mouse.isDown 1) (love.mouse.isDown 2))) (set state.dragging? false)))

(fn drag-slider! [x]
  ;; The dragged item belongs to the layout of the scene as it was; the parameter
  ;; is found again by name in the scene as it is now.
  (let [item state.panel.drag
        p (accumulate [found nil _ q (ipairs (or (?. state.scene :params) [])) &until found]
            (when (= q.name item.param.name) q))]
    (when p
      (let [live (doto (collect [k v (each-pair item)] k v) (tset :param p))
            v (panel.with-value live (panel.slider-value live x))]
        (when (not (params.same-value? v p.value))
          (set-parameter! p v))))))

(fn mousemoved [x _ dx dy]
  (if state.panel.drag
      (drag-slider! x)
      (and state.cam state.dragging?)
      (do (camera.turn! state.cam (* dx mouse-degrees-per-pixel))
          (camera.pitch! state.cam (* dy mouse-degrees-per-pixel)))))

;;; Drawing

(fn coarse? []
  "True when the picture on screen is a whole low-resolution one (the state changed
this frame or the last), not the full resolution being refined."
  (and state.picture state.move-canvas (= state.picture.canvas state.move-canvas)))

(fn whole? []
  "True when the full-resolution picture is whole (its still may follow)."
  (and state.refine (progress.complete? state.refine.progress)))

(fn idle? []
  "True when nothing is left to draw for the picture on screen: it is whole, and
its still is drawn, or there is none, or its shader is not ready yet (a helper
builds it). While its state stays, a frame only shows it again."
  (and (whole?)
       (case state.refine.still
         {:progress p} (progress.complete? p)
         _ true)))

(fn still-whole? []
  "True when the still of the picture on screen is drawn whole."
  (case (?. state.refine :still)
    {:progress p} (progress.complete? p)
    _ false))

(fn background-done? []
  "True when nothing is left to do for the state on screen (scripts wait for it): the
picture is whole, its still is drawn or there is none, no load waits, and the compile
helper has no job running or waiting (the folded shader asked for, when there is one)."
  (let [w state.warm
        memo state.plan-memo]
    (and (idle?) (not state.pending) (not state.waiting-since)
         (not= nil (?. state.refine :still))
         (or (not w) (not w.enabled?)
             (and (not w.running) (not w.queued)
                  (not (?. w.background :running)) (not (?. w.background :queued))
                  (or (not (?. memo :plan :tape)) (not= nil memo.folded)))))))

(fn warm-interpreter-when-idle! []
  "Once the scene on screen has nothing left to do (its still drawn and the helper
idle, or its clock runs: no still then), have the helper build the interpreter's
shader for it, if it is not built: after the still and the folded shader, which the
window shows, not before them."
  ;; Asked once per load, view, model and reflection count (a value edit or the
  ;; clock makes a new scene, not another shader).
  (local asked (.. state.reloads " " state.view " " (tostring state.classic?) " " state.reflections))
  (when (and state.interpret-edits? state.scene (not= state.interpreter-asked asked)
             (not state.interpreting)
             (or (background-done?)
                 (let [w state.warm]
                   (and (scene-mod.animated? state.scene) (not state.paused?)
                        (not state.pending) w (not w.running) (not w.queued)
                        (not (?. w.background :running)) (not (?. w.background :queued))))))
    (set state.interpreter-asked asked)
    (warm-interpreter! state.scene state.reflections)))

(fn waiting-for? [key]
  "Whether the state to show next waits for a helper to compile shader `key`: a
load's, or the new plan's of the scene on screen (a view, a switch)."
  (if state.pending (= key state.pending.key)
      state.waiting-since (case (current-plan)
                            plan (and (= key plan.key) (compile-waits? state.scene plan)))
      false))

(fn preview-picture []
  "The newest preview of the state waiting for its helper, while the camera stays
where it was when the preview was asked for (a moved camera shows the last scene
live instead); nil when there is none."
  (let [r state.preview-request]
    (when (and r (waiting-for? r.key))
      (case (preview.poll! state.preview)
        latest (when (and (= latest.id r.id) (= r.cam-key (adaptive.camera-key state.cam)))
                 latest)))))

(fn hud-lines []
  (let [cam state.cam
        canvas state.canvas
        lines [(string.format "%d fps  %.1f ms" (love.timer.getFPS)
                              (* 1000 (love.timer.getAverageDelta)))]]
    ;; This frame's preview (draw found it before the HUD is drawn).
    (case state.shown-preview
      p (table.insert lines (string.format "preview %dx%d: the new scene by the CPU reference (%.0f ms) while a helper compiles its shader"
                                           p.w p.h (* 1000 p.seconds))))
    (if (coarse?)
        (table.insert lines
                      (if state.adaptive.out-of-reach?
                          (string.format "%dx%d while changing: %d fps is out of reach (%.0f ms a frame go to the window, HUD and Lua)"
                                         (state.move-canvas:getWidth) (state.move-canvas:getHeight)
                                         state.interactive-fps (* 1000 (or state.adaptive.fixed 0)))
                          (string.format "%dx%d while changing (holding %d fps; full scale %.2f)"
                                         (state.move-canvas:getWidth) (state.move-canvas:getHeight)
                                         state.interactive-fps state.scale)))
        canvas
        (table.insert lines (string.format "%dx%d (scale %.2f)%s" (canvas:getWidth)
                                           (canvas:getHeight) state.scale
                                           (case (?. state.refine :still)
                                             {:progress p} (if (progress.complete? p)
                                                               (.. ", anti-aliased (" (quality.label still-samples true) ")") "")
                                             _ ""))))
    (when state.scene
      (table.insert lines (.. "scene: " (text.printable state.scene.name 80) "  view: " state.view
                              (if state.scene.lighting
                                  (if state.classic? "  lighting: classic" "  lighting: modern")
                                  "  lighting: classic")
                              ;; Which shader draws: the values as uniforms, or folded
                              ;; into constants once they settled (folded-plan).
                              (if (?. state.drawn :plan :tape)
                                  (if state.drawn.plan.base-key "  values: folded"
                                      "  values: uniforms")
                                  "")))
      (table.insert lines (string.format "reflections: %d  fov: %.1f" state.reflections cam.fov))
      (table.insert lines (hud.camera-line cam)))
    (when (and (?. state.scene :params) (not state.panel.open?))
      (table.insert lines (string.format "F2: %d parameter%s" (length state.scene.params)
                                         (if (= 1 (length state.scene.params)) "" "s"))))
    (when (and state.scene (scene-mod.animated? state.scene))
      (table.insert lines (string.format "t = %.2f s%s" state.time
                                         (if state.paused? " (paused; space plays, . steps)"
                                             " (space pauses; paused, the picture sharpens)"))))
    (case (?. state.refine :progress)
      p (when (and (not (coarse?)) (not (progress.complete? p)))
          (table.insert lines (string.format "refining: %d bands, one per frame (%.0f%% drawn)"
                                             (progress.bands p) (* 100 (progress.covered p))))))
    (when (and (not (coarse?)) (whole?))
      (case state.refine.still
        {:progress p} (when (not (progress.complete? p))
                        (table.insert lines (string.format "anti-aliasing: %d bands (%.0f%% drawn)"
                                                           (progress.bands p) (* 100 (progress.covered p)))))
        nil (when (not= false (?. state.plan-memo :still))
              (table.insert lines "anti-aliasing: its shader is compiling in a helper process"))))
    (when state.last-load
      (table.insert lines (string.format "last load: %.0f ms (%s)%s, %d so far"
                                         state.last-load.ms
                                         (if state.last-load.interpreted? "drawn by the tape interpreter"
                                             (not state.last-load.compiled?) "uniforms only"
                                             state.last-load.helper? "shader compiled by a helper"
                                             "shader compiled")
                                         (case state.last-load.first-ms
                                           ms (string.format "; first picture %.0f ms later" ms)
                                           _ "")
                                         state.reloads)))
    (case (or (?. state.pending :start) state.waiting-since)
      since (table.insert lines (string.format "compiling the new shader in a helper process (%.1f s)%s"
                                               (- (love.timer.getTime) since)
                                               (if state.interpreting
                                                   "; the tape interpreter draws the new scene meanwhile"
                                                   ""))))
    (let [now (love.timer.getTime)]
      (each [_ m (ipairs state.messages)]
        (when (< now m.until) (table.insert lines m.text))))
    lines))

(fn draw-text-box [message x y color]
  ;; LÖVE's text layout raises on invalid UTF-8: everything shown goes through
  ;; text.printable, and is cut to a screenful.
  (let [font (love.graphics.getFont)
        message (text.printable (if (> (length message) 4000) (message:sub 1 4000) message))
        (width wrapped) (font:getWrap message (- (love.graphics.getWidth) (* 2 x) 16))
        h (* (length wrapped) (font:getHeight))]
    (love.graphics.setColor 0 0 0 0.6)
    (love.graphics.rectangle :fill x y (+ width 16) (+ h 12))
    (love.graphics.setColor (. color 1) (. color 2) (. color 3) (. color 4))
    (love.graphics.printf message (+ x 8) (+ y 6) (+ width 1))
    (love.graphics.setColor 1 1 1 1)))

(fn prepare-despeckle! []
  "Compile the despeckle shader (see despeckled) once, at the start: compiled at its
first use, mid-play, it would be a compile of the player's own after the first load."
  (when (= nil state.despeckle)
    (set state.despeckle
         (case (pcall love.graphics.newShader
                      (pick-values 1 (love.filesystem.read "shaders/player/despeckle.glsl")))
           (true shader) {: shader}
           _ false))))

(fn despeckled [canvas]
  "`canvas` with each pixel clamped to its four neighbours' range
(shaders/player/despeckle.glsl: a lone firefly goes, edges and lines stay), drawn into
a canvas of the same size kept for the next frame; `canvas` itself when the shader
cannot be made."
  (prepare-despeckle!)
  (if (not state.despeckle)
      canvas
      (let [d state.despeckle
            (w h) (canvas:getDimensions)]
        (when (or (not d.canvas) (not= w (d.canvas:getWidth)) (not= h (d.canvas:getHeight)))
          (when d.canvas (d.canvas:release))
          (set d.canvas (love.graphics.newCanvas w h)))
        (d.canvas:setFilter (canvas:getFilter))
        (love.graphics.push :all)
        (love.graphics.setCanvas d.canvas)
        (love.graphics.setBlendMode :replace)
        (love.graphics.setShader d.shader)
        (d.shader:send :texelSize [(/ 1 w) (/ 1 h)])
        (love.graphics.setColor 1 1 1 1)
        (love.graphics.draw canvas 0 0)
        (love.graphics.pop)
        d.canvas)))

(fn draw-stretched [canvas]
  ;; Stretched to the window exactly: the canvas is the window times the scale
  ;; rounded down, and 1 / scale would leave strips at the right and bottom. A picture
  ;; smaller than the window (the moving picture, a lower render scale) is despeckled
  ;; first: stretched, one firefly pixel would become a blob many pixels wide.
  (let [(ww wh) (love.graphics.getDimensions)
        shown (if (< (* 4 (canvas:getWidth)) (* 3 ww)) (despeckled canvas) canvas)]
    (love.graphics.setColor 1 1 1 1)
    (love.graphics.draw shown 0 0 0 (/ ww (shown:getWidth)) (/ wh (shown:getHeight)))))

(fn state-key [memo-id]
  "The scene state a picture shows: the scene's values (their generation, which the
clock of an animated scene moves too), the plan (view, reflections, model: the folded
twin of a plan draws the same state), the camera and the picture's size."
  (let [(ww wh) (love.graphics.getDimensions)]
    (string.format "%d %d %s %dx%d %.6g" state.generation memo-id
                   (adaptive.camera-key state.cam) ww wh state.scale)))

(fn render-timed! [canvas scene plan ?rows ?extra]
  "Draw into `canvas` (the rows `?rows` only, when given; `?extra` uniforms as
frame.render-to-canvas! takes them) and wait for the renderer to finish: the
seconds it took, or nil when it failed (the error is shown)."
  (let [start (love.timer.getTime)]
    (case (frame.render-to-canvas! state.cache canvas scene plan state.cam ?rows ?extra)
      (nil err) (do (set state.error err) nil)
      ;; Reading one pixel back waits for the renderer, so the time is the render's.
      _ (let [data (canvas:newImageData 1 1 0 0 1 1)]
          (data:release)
          (- (love.timer.getTime) start)))))

(fn draw-coarse! [scene plan key]
  "A new state: its whole picture now, at the scale that holds the target rate (or a
small one for a shader not measured yet)."
  (when (not (adaptive.known? state.adaptive plan.key)) (probe! scene plan))
  (let [(ww wh) (love.graphics.getDimensions)
        ;; A loaded scene's first frame also pays for what the model has not seen yet
        ;; (the HUD's first text, the new canvases): its picture gets half the time.
        target (/ (if state.first-picture 0.5 1) state.interactive-fps)
        s (adaptive.scale-for state.adaptive plan.key target (* ww wh) state.scale)
        canvas (ensure-move-canvas! s)]
    (case (render-timed! canvas scene plan)
      seconds (do (set state.last-render {:shader plan.key :coarse? true :seconds seconds
                                          :pixels (* (canvas:getWidth) (canvas:getHeight))})
                  (set state.picture {: key : canvas})
                  (set state.refine nil)
                  (when state.first-picture (set state.first-picture.drawn? true))))))

(fn refined! [r canvas]
  "The full-resolution picture of `r` is whole: say how the frames went while the
state changed, and how long the refinement took."
  (when (> (length state.move-times) 1)
    (say! (string.format "changing: %d frames at %dx%d, median %.0f ms; full %dx%d %.0f ms after it stayed"
                         (length state.move-times)
                         (if state.move-canvas (state.move-canvas:getWidth) 0)
                         (if state.move-canvas (state.move-canvas:getHeight) 0)
                         (* 1000 (or (median state.move-times) 0))
                         (canvas:getWidth) (canvas:getHeight)
                         (* 1000 (- (love.timer.getTime) r.start)))))
  (set state.move-times []))

(fn band-schedule [canvas shader-key]
  "Bands over the whole of `canvas` for the shader `shader-key`, each sized by what
the frame-time model says it costs: a band frame's render gets what the frame's
other work leaves of the budget."
  (progress.new (canvas:getHeight)
                (adaptive.render-seconds state.adaptive shader-key
                                         (* (canvas:getWidth) (canvas:getHeight)))
                (math.max (* 0.25 progress.budget)
                          (- progress.budget (or state.adaptive.fixed 0)))))

(fn draw-band! [p canvas scene plan ?extra]
  "Draw the next band of schedule `p` into `canvas` with `plan` (and `?extra`
uniforms): the seconds it took, or nil when it failed (the error is shown)."
  (let [(y0 y1) (progress.rows p)]
    (case (render-timed! canvas scene plan [y0 y1] ?extra)
      seconds (do (progress.drawn! p y0 y1 seconds)
                  (set state.last-render {:shader plan.key :band? true :seconds seconds
                                          :pixels (* (canvas:getWidth) (- y1 y0))})
                  seconds))))

(fn start-refine! [plan key]
  "The state on screen stayed: the full resolution starts from its whole coarse
picture, scaled up, and is refined in bands of that same state."
  (let [canvas (ensure-canvas!)
        from state.picture.canvas
        whole? (and (= (from:getWidth) (canvas:getWidth)) (= (from:getHeight) (canvas:getHeight)))
        p (band-schedule canvas plan.key)]
    (love.graphics.push :all)
    (love.graphics.setCanvas canvas)
    (love.graphics.setColor 1 1 1 1)
    (love.graphics.draw from 0 0 0 (/ (canvas:getWidth) (from:getWidth))
                        (/ (canvas:getHeight) (from:getHeight)))
    (love.graphics.pop)
    ;; A coarse picture already at full resolution (a light scene) is the picture.
    (set state.refine {: key :progress p :start (love.timer.getTime)})
    (set state.picture {: key : canvas})
    (when whole?
      (set p.next p.height)
      (refined! state.refine canvas))))

(fn refine-step! [scene plan]
  "One band of the full-resolution picture being refined; nothing once it is whole."
  (let [r state.refine
        p r.progress
        canvas state.canvas]
    (when (not (progress.complete? p))
      (draw-band! p canvas scene plan)
      (when (progress.complete? p)
        (refined! r canvas)))))

(fn still-of [scene plan]
  "The still's twin of `plan` (the plan on screen), once its shader is compiled or
its helper is done; nil while the helper builds it; false when there is none: a
plan that samples more than once already, a view without shading, no helper (a
compile in the window's process would freeze it), a failed build."
  (let [memo state.plan-memo]
    (if (or (not memo) (> (or plan.samples 1) 1) (not= plan.view :shaded)
            (not (?. state.warm :enabled?)))
        false
        ;; None for the interpreter's picture: the helper's shader comes next.
        state.interpreting nil
        (do
          (when (= nil memo.still)
            (let [(still) (plan-with scene state.reflections (not= nil plan.base-key) true)]
              (set memo.still (or still false))))
          (case memo.still
            false false
            still (if (gpu.cached? state.cache still) still
                      ;; Not while a load waits for its shader: the edit lane first.
                      (or state.pending state.waiting-since) nil
                      (warm.ready? state.warm still.key #(warm-source scene still) true)
                      (if (= :failed (warm.status state.warm still.key)) false still)
                      nil))))))

(fn prior-copy! [canvas]
  "A copy of `canvas` (the whole full-resolution picture: one ray through each
pixel's centre) for the still to read (uniforms.prior), in a canvas kept for it."
  (let [(w h) (canvas:getDimensions)]
    (when (or (not state.prior-canvas) (not= w (state.prior-canvas:getWidth))
              (not= h (state.prior-canvas:getHeight)))
      (when state.prior-canvas (state.prior-canvas:release))
      (set state.prior-canvas (love.graphics.newCanvas w h))
      (state.prior-canvas:setFilter :nearest :nearest))
    (love.graphics.push :all)
    (love.graphics.setCanvas state.prior-canvas)
    ;; A plain copy, whatever was set before: no shader, no scissor, no blending.
    (love.graphics.setShader)
    (love.graphics.setScissor)
    (love.graphics.setBlendMode :replace)
    (love.graphics.setColor 1 1 1 1)
    (love.graphics.draw canvas 0 0)
    (love.graphics.pop)
    state.prior-canvas))

(fn still-step! [scene plan]
  "The full-resolution picture is whole and its state stays: one band of its
anti-aliased still (see still-samples), once the still's shader is ready. The still
reads the whole picture (its centre rays) to find the pixels that an edge crosses."
  (let [r state.refine
        canvas state.canvas]
    (when (= nil r.still)
      (case (still-of scene plan)
        false (set r.still false)
        still (do (when (not (adaptive.known? state.adaptive still.key)) (probe! scene still))
                  (set r.still {:plan still :start (love.timer.getTime)
                                :prior (uniforms.prior 2 (prior-copy! canvas))
                                :progress (band-schedule canvas still.key)}))))
    (case r.still
      {:plan still :progress p}
      (when (not (progress.complete? p))
        ;; A still that fails to draw is given up; the picture stays whole.
        (when (not (draw-band! p canvas scene still r.still.prior))
          (set r.still false))
        (when (and r.still (progress.complete? p))
          (say! (string.format "anti-aliased still: %dx%d in %.1f s" (canvas:getWidth)
                               (canvas:getHeight) (- (love.timer.getTime) r.still.start))))))))

(fn draw-scene! [scene plan key]
  "Draw the frame of state `key`: never a picture that mixes two states."
  (if (and (= key (?. state.refine :key)) (progress.complete? state.refine.progress))
      (still-step! scene plan)
      (= key (?. state.refine :key)) (refine-step! scene plan)
      (= key (?. state.picture :key)) (do (start-refine! plan key) (refine-step! scene plan))
      (draw-coarse! scene plan key))
  (when state.picture (draw-stretched state.picture.canvas)))

(fn shown []
  "The scene and plan to draw, and the id of the plan (see state-key): the scene's
own, or while a helper compiles the shader of a new plan (a view or a switch changed
the shader), the last ones drawn."
  (case (current-plan)
    (nil err) (values nil err)
    plan (if (compile-waits? state.scene plan)
             (do (when (not state.waiting-since)
                   (set state.waiting-since (love.timer.getTime))
                   ;; The new state by the CPU reference until its shader is ready.
                   (when (and state.preview (not state.pending))
                     (request-preview! state.scene state.reflections state.cam plan.key
                                       state.waiting-since)))
                 (values state.drawn.scene state.drawn.plan state.drawn.id))
             (do (when (and state.waiting-since state.preview (not state.pending))
                   (preview.cancel! state.preview)
                   (set state.preview-request nil))
                 (set state.waiting-since nil)
                 (values state.scene (or (folded-plan plan) plan) state.plan-memo.id)))))

(fn draw-preview! [p]
  ;; The preview picture `p` stretched to the window; the first time each is drawn,
  ;; how long after the load started (the edit read) it came. Not despeckled as the
  ;; moving picture is (draw-stretched): that pass, first used on a preview, made
  ;; llvmpipe build its code for another texture, 80 ms before the first preview
  ;; showed (gallery), and a preview is on screen for a fraction of a second.
  (let [(ww wh) (love.graphics.getDimensions)]
    (love.graphics.setColor 1 1 1 1)
    (love.graphics.draw p.image 0 0 0 (/ ww p.w) (/ wh p.h)))
  (when (not= (?. state.previewed :image) p.image)
    (let [now (love.timer.getTime)
          ms (* 1000 (- now state.preview-request.since))]
      (set state.previewed {:id p.id :image p.image :w p.w :h p.h :ms ms :at now
                            :seconds p.seconds
                            ;; The request's first picture (edit-latency reports it).
                            :first (if (= p.id (?. state.previewed :id)) state.previewed.first
                                       {:at now :w p.w :h p.h})})
      (when (not state.quiet?)
        (print (string.format "preview of %s on screen %.0f ms after the change (%dx%d, drawn in %.0f ms by the CPU reference)"
                              (or (?. state.pending :path) state.path) ms p.w p.h (* 1000 p.seconds)))))))

(fn draw-scene-or-last! []
  (when state.scene
    (case (shown)
      (nil err) (set state.error err)
      (scene plan id) (let [key (state-key id)]
                        (if (and (or state.pending state.waiting-since) state.picture
                                 (= key state.picture.key))
                            ;; Waiting for a helper, the state on screen unchanged: the
                            ;; picture again, not refined further; the cores go to the helper.
                            (do (love.timer.sleep 0.01) (draw-stretched state.picture.canvas))
                            (do (when (and (idle?) (= key state.refine.key))
                                  ;; Whole and current: shown again, nothing drawn; no
                                  ;; need to spin.
                                  (love.timer.sleep 0.005))
                                (draw-scene! scene plan key)))
                        (when (and (or (not= scene (?. state.drawn :scene))
                                       (not= plan (?. state.drawn :plan)))
                                   (gpu.cached? state.cache plan))
                          (set state.drawn {: scene : plan : id}))))))

(fn draw-overlays! []
  (when state.hud?
    (draw-text-box (table.concat (hud-lines) "\n") 8 8 [1 1 1 1]))
  (case (panel-layout)
    lay (panel.draw! lay (parameter-status)))
  (when state.error
    (draw-text-box (.. state.error
                       (if state.scene
                           "\n(the last good scene keeps running; saving the file reloads it)"
                           "\n(saving a fixed file loads it; [ and ] open the other scenes)"))
                   8 (- (love.graphics.getHeight) 120) [1 0.45 0.4 1])))

(fn draw []
  (case (when state.scene (preview-picture))
    ;; The cores go to the helper and the preview thread.
    p (do (love.timer.sleep 0.01) (draw-preview! p) (set state.shown-preview p))
    _ (do (set state.shown-preview nil) (draw-scene-or-last!)))
  (draw-overlays!))

(var frame-serial 0)

(fn log-frame! [out]
  "One line on `out` for the frame just drawn (RAYMARCH_FRAME_LOG, read by
tools/edit-window.sh): the wall-clock time (filestat.now, the clock of a file's
mtime), what drew it (preview: the CPU reference's picture of the new scene while
its shader is compiled; interpreter; shader) and the serial number of the scene
it shows (each text of the file gets the next one when it is first drawn: a load
that waited for its helper may run the file again, another table of the same scene)."
  (let [scene (if state.shown-preview (or (?. state.pending :scene) state.scene)
                  (?. state.drawn :scene))
        source (when scene (. scene-texts scene))
        serial (when source
                 (when (not (. frame-serials source))
                   (set frame-serial (+ frame-serial 1))
                   (tset frame-serials source frame-serial))
                 (. frame-serials source))]
    (out:write (string.format "%.6f %s %d\n" (filestat.now)
                              (if state.shown-preview :preview
                                  state.interpreting :interpreter
                                  :shader)
                              (or serial 0)))
    (out:flush)))

(fn shoot-and-quit! [path]
  ;; The captured window includes the HUD and any error overlay: what a player sees.
  (love.graphics.captureScreenshot
    (fn [data]
      (let [bytes (: (data:encode :png) :getString)]
        (case (output.write! path bytes {:protect [state.path] :label (.. "--shot " path)})
          true (do (print (.. "wrote " path)) (love.event.quit 0))
          (nil err) (do (io.stderr:write (.. "error: " err "\n"))
                        (love.event.quit 1)))))))

(fn frame-measured! [dt]
  "`dt` is the last frame's whole time: feed it, with that frame's render, to the
frame-time model (and the band schedule); say when a loaded scene's first picture
reached the screen."
  (case state.last-render
    r (do (adaptive.measured! state.adaptive r.shader r.pixels r.seconds dt)
          (when r.coarse? (table.insert state.move-times dt))
          (set state.last-render nil)))
  (case state.first-picture
    {: since :drawn? true : path}
    (let [ms (* 1000 (- (love.timer.getTime) since))]
      (set state.first-picture nil)
      (when state.last-load (set state.last-load.first-ms ms))
      (when (not state.quiet?)
        (print (string.format "first picture of %s on screen %.0f ms after its shader was ready (%dx%d)"
                               path ms (if state.move-canvas (state.move-canvas:getWidth) 0)
                               (if state.move-canvas (state.move-canvas:getHeight) 0)))))))

(fn prepare-font! []
  ;; The HUD's glyphs are rasterized at their first use; done here, the first
  ;; picture's frame does not pay for them (about 18 ms on llvmpipe).
  (let [canvas (love.graphics.newCanvas 8 8)
        ascii (table.concat (fcollect [c 32 126] (string.char c)))]
    (love.graphics.push :all)
    (love.graphics.setCanvas canvas)
    (love.graphics.print ascii 0 0)
    (love.graphics.pop)
    (canvas:release)))

(fn start! [options]
  "Play the scene file named in `options.scene`: install the LÖVE callbacks."
  (set state.cache (gpu.new-cache))
  ;; What the player prints reaches a log as it happens, not when it quits.
  (io.stdout:setvbuf :line)
  (prepare-font!)
  (prepare-despeckle!)
  (set state.warm (when options.warm? (warm.new)))
  (set state.preview (when options.warm? (preview.new)))
  ;; The interpreter draws edits on a GPU, where a branch all pixels take alike costs
  ;; only its own case. Not on a software renderer: llvmpipe runs every case of the
  ;; interpreter's switch for each instruction (organic at 160x90: 10.7 s a frame
  ;; against 16 ms compiled, docs/benchmarks.md); there the CPU previews show an
  ;; edit. --interpret-edits forces it (the tests).
  (set state.interpret-edits?
       (and (not= nil state.warm)
            (or (= true options.interpret-edits?)
                (not (plan-mod.software-renderer? (select 4 (love.graphics.getRendererInfo)))))))
  (set love.quit (fn [] (when state.preview (preview.stop! state.preview)) false))
  (set state.interactive-fps (or options.target-fps default-interactive-fps))
  ;; A load waits for the scene worker (up to its deadline of 5 s): escape and the
  ;; window's close button still quit meanwhile (other input is dropped).
  (worker.set-waiting! (fn []
                         (show-opening! "running the scene file in the worker")
                         (love.event.pump)
                         (var quit? false)
                         (each [name a (love.event.poll)]
                           (when (or (= name :quit) (and (= name :keypressed) (= a :escape)))
                             (set quit? true)))
                         (when quit? (set state.quitting? true) (love.event.quit 0))
                         quit?))
  (set state.opening {:path options.scene :start (love.timer.getTime)})
  (show-opening! "reading the file" true)
  (load! options.scene true)
  ;; A screenshot of a file caught mid-write waits (2 s at most) for its retry.
  (let [deadline (+ (love.timer.getTime) 2)]
    (while (and options.shot (not state.scene) (?. state.watch :retry?)
                (< (love.timer.getTime) deadline))
      (love.timer.sleep 0.02)
      (set state.poll-at 0)
      (poll-file!)))
  ;; Not when quitting: LÖVE exiting a few ms after the helper's thread started
  ;; crashed (exit 139, 2 runs of 2 in tools/check-stuck-worker.sh).
  (when (and state.warm (not state.quitting?)) (warm.prepare! state.warm))
  ;; The preview thread starts now, and draws the first scene's smallest picture at
  ;; once, unseen: LuaJIT has then compiled the reference's code when the first edit
  ;; comes (that edit's first preview came after 150-230 ms, the next ones' after
  ;; 45-90; twisted-tower and organic).
  (when (and state.preview state.scene (not state.quitting?))
    (let [(ww wh) (love.graphics.getDimensions)]
      (preview.request! state.preview state.scene (plan-options state.reflections)
                        state.cam (/ ww wh) 1)))
  (when (and options.shot (not state.scene))
    ;; Nothing to shoot: a script waits on this run, so fail like --render does.
    (io.stderr:write (.. "error: " (or state.error (.. options.scene ": no scene")) "\n"))
    (love.event.quit 1))
  (set love.update (fn [dt]
                     ;; Nothing to render (a broken or missing first scene): the
                     ;; message is on screen; do not spin at hundreds of frames a second.
                     (when (not state.scene) (love.timer.sleep 0.05))
                     (frame-measured! dt)
                     (poll-file!)
                     (finish-pending!)
                     (warm-interpreter-when-idle!)
                     (mesh-pending!)
                     (advance-time! dt)
                     (when state.cam
                       (handle-keyboard dt)
                       (handle-gamepad dt))))
  (var frames 0)
  ;; A log that cannot be written ends the run: a measurement without it is none.
  (local frame-log (when frame-log-path
                     (case (io.open frame-log-path :w)
                       f f
                       (nil err) (do (io.stderr:write (.. "error: RAYMARCH_FRAME_LOG: " err "\n"))
                                     (love.event.quit 1)
                                     nil))))
  (set love.draw (fn []
                   (draw)
                   (when frame-log (log-frame! frame-log))
                   (set frames (+ frames 1))
                   ;; Shoot once N frames are drawn and the image is whole (a
                   ;; progressive image needs every band drawn).
                   (when (and options.shot (not state.shooting?) (>= frames options.frames)
                              (or (not state.scene) (idle?)))
                     (set state.shooting? true)
                     (shoot-and-quit! options.shot))))
  (set love.keypressed keypressed)
  (set love.gamepadpressed gamepadpressed)
  (set love.mousemoved mousemoved)
  (set love.mousepressed mousepressed)
  (set love.mousereleased mousereleased)
  (set love.joystickadded (fn [j] (when (j:isGamepad) (set state.gamepad j)))))

{: start! : state : load! : poll-file! : current-plan : whole? : still-whole? : background-done?
 : interpreter-ready : coarse?}

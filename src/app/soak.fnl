;; `love . --soak [SCENE] [--cycles N]`: drives the player's own hot-reload path
;; headless. First the edits a person makes to SCENE (default scenes/seed.fnl), then N
;; cycles of a value edit, a structural edit and a broken version of a generated scene,
;; each picked up by the file watcher and rendered; it checks what a player would see
;; and reports reload times, Lua memory and live shaders.

(local status (require :src.util.status))
(local play (require :src.app.play))
(local frame (require :src.backend.frame))
(local filestat (require :src.util.filestat))
(local camera (require :src.render.camera))
(local {: median} (require :src.util.stats))
(local {: temp-scene-path : write!} (require :src.app.scripted))

(local structures 12)   ; distinct sphere counts, more than the shader cache holds

(fn scene-text [{: spheres : shade}]
  (let [objects (fcollect [i 1 spheres]
                  (string.format "{:kind :sphere :radius 0.8 :pos [%d 0 0.8] :color [%.3f 0.3 0.2]}"
                                 (* 2 (- i 1)) (if (= i 1) shade 0.5)))]
    (.. "{:name \"soak\"\n"
        " :camera {:pos [0 -8 1] :yaw 90 :pitch 0 :fov 60}\n"
        " :light {:pos [-6 -12 10]}\n"
        " :render {:reflections 1}\n"
        " :objects [" (table.concat objects "\n           ")
        "\n           {:kind :plane :height 0 :color [0.6 0.6 0.6]}]}\n")))

(local broken-texts
  ;; Each fails on line 2: a syntax error, a validation error, and hostile files
  ;; (compile-time code in a key, a vector with holes, bytes that are not UTF-8, a
  ;; terminal escape in a key, a library call past its cap).
  ["{:name \"soak\"\n :objects [{:kind :sphere :radius 1}\n"
   "{:name \"soak\"\n :objects [{:kind :sphere :radius -1}]}\n"
   "{:name \"soak\"\n (eval-compiler (while true nil)) 1 :objects []}\n"
   "{:name \"soak\"\n :camera {:pos [nil nil 5]} :objects []}\n"
   "{:objects []\n :name \"\255\254\"}\n"
   "{:objects []\n \"\027[2J\027[31mFAKE\" 1}\n"
   "{:objects []\n :name (table.concat (fcollect [i 1 3] (string.rep \"x\" 999999)))}\n"])

(fn broken-text [i]
  (. broken-texts (+ 1 (% i (length broken-texts)))))


(fn centre-pixel [canvas]
  (let [data (canvas:newImageData)
        (r g b) (data:getPixel (math.floor (/ (canvas:getWidth) 2))
                               (math.floor (/ (canvas:getHeight) 2)))]
    (data:release)
    [(math.floor (+ 0.5 (* 255 r))) (math.floor (+ 0.5 (* 255 g))) (math.floor (+ 0.5 (* 255 b)))]))

(fn same-pixel? [a b]
  (and (= (. a 1) (. b 1)) (= (. a 2) (. b 2)) (= (. a 3) (. b 3))))

(fn canvas-bytes [canvas]
  (let [data (canvas:newImageData)
        bytes (data:getString)]
    (data:release)
    bytes))

(fn edit-check! [o check]
  "The edits a person makes to a real scene file (o.scene, a copy in a temp file):
recolour a sphere, add a sphere, break the file, fix it. Prints one line per step."
  (let [state play.state
        path (temp-scene-path)
        canvas (love.graphics.newCanvas 128 112)
        original (frame.read-text o.scene)
        ;; A sphere's colour, or else the first colour in the file.
        recoloured (let [(text n) (original:gsub "(:kind :sphere[^}]-:color %[)[^%]]*%]" "%11 1 0]" 1)]
                     (if (> n 0) text
                         (pick-values 1 (original:gsub "(:color%s*%[)[^%]]*%]" "%11 1 0]" 1))))
        ;; The added sphere sits 6 units in front of the file's camera, so it shows.
        [ax ay az] (case (frame.load-scene o.scene)
                     scene (let [[px py pz] scene.camera.pos
                                 [fx fy fz] (camera.basis (camera.from-scene scene))]
                             [(+ px (* 6 fx)) (+ py (* 6 fy)) (+ pz (* 6 fz))])
                     _ [0 0 14])
        sphere (string.format "{:kind :sphere :radius 1 :pos [%.6f %.6f %.6f] :color [1 1 1]}"
                              ax ay az)
        ;; A literal list gets the sphere first; a list built in code (`:objects ring`)
        ;; gets it inserted by a `let` around the name.
        added (let [(text n) (recoloured:gsub ":objects%s*%[" (.. ":objects [" sphere "\n") 1)]
                (if (> n 0) text
                    (pick-values 1 (recoloured:gsub ":objects%s+([%a_][%w_%-]*)"
                                                    (.. ":objects (let [o %1] (table.insert o 1 "
                                                        sphere ") o)")
                                                    1))))
        broken (recoloured:gsub "}%s*$" "")]
    (fn step! [text]
      ;; The clock moved forward instead of waiting: first too soon (nothing loads),
      ;; then past the settle time.
      (write! path text)
      (play.poll-file! (+ (filestat.now) 0.01))
      (play.poll-file! (+ (filestat.now) 0.3))
      (case (play.current-plan)
        plan (frame.render-to-canvas! state.cache canvas state.scene plan state.cam))
      (canvas-bytes canvas))
    (fn report [what ok?]
      (print (.. "reload check, " o.scene ": " what ": " (if ok? "ok" "FAILED")))
      (check ok? (.. o.scene ": " what)))
    (write! path original)
    (play.load! path true)
    (let [image0 (step! original)
          compiles0 state.cache.compiles
          image1 (step! recoloured)]
      (report "recolouring an object changes the next frame without a shader compile"
              (and (not= image0 image1) (= state.cache.compiles compiles0)
                   (= state.error nil) (not= recoloured original)))
      (let [image2 (step! added)]
        (report "adding a sphere compiles a new shader and shows it"
                (and (= state.cache.compiles (+ compiles0 1)) (not= image2 image1)
                     (= state.error nil))))
      (step! recoloured)
      (let [image3 (step! broken)]
        (report "breaking the file shows file:line and keeps the last image"
                (and state.error (= (state.error:find path 1 true) 1)
                     (not= nil (state.error:match "^[^:]+:%d+:")) (= image3 image1)))
        (print (.. "  the overlay says: " (tostring state.error))))
      (let [image4 (step! recoloured)]
        (report "fixing the file clears the message and renders again"
                (and (= state.error nil) (= image4 image1))))
      ;; A custom node's parameter is a uniform: its edit compiles nothing.
      (let [(param-edit n) (recoloured:gsub "(:kind :custom[^\n]-\n?[^\n]-:params {:[%w%-]+ )([%d%.]+)"
                                            #(.. $1 (* 1.25 (tonumber $2))) 1)]
        (when (> n 0)
          (let [compiles state.cache.compiles
                image (step! param-edit)]
            (report "editing a custom node's :params value changes the next frame without a shader compile"
                    (and (not= image image1) (= state.cache.compiles compiles) (= state.error nil))))
          (step! recoloured)))
      ;; A file still being written is not loaded, however late the poll: half of it,
      ;; written just now, polled at once and again a second later (a slow player)
      ;; after the writer wrote the same half again.
      (let [half (recoloured:sub 1 (math.floor (/ (length recoloured) 2)))
            reloads state.reloads]
        (write! path half)
        (play.poll-file! (filestat.now))
        (write! path half)
        (play.poll-file! (+ (filestat.now) 0.1))
        (report "a file being rewritten is not loaded half-written, whatever the poll rate"
                (and (= state.reloads reloads) (= state.error nil)))
        (write! path recoloured)
        (play.poll-file! (+ (filestat.now) 0.3)))
      ;; A load that catches the file mid-write (one finishing after a compile, F5
      ;; pressed as the editor saves): another process writes the file in two halves
      ;; 50 ms apart, the player loads it as soon as the first half is there, then
      ;; polls on the real clock. No error at any time, and the whole file in the end.
      (let [cut (math.floor (/ (length original) 2))
            first-half (original:sub 1 cut)
            [h1 h2] [(.. path ".half1") (.. path ".half2")]
            errors []
            note-error! #(when (and state.error (not= state.error (. errors (length errors))))
                           (table.insert errors state.error))]
        (write! h1 first-half)
        (write! h2 (original:sub (+ cut 1)))
        (os.execute (string.format "(cat '%s' > '%s'; sleep 0.05; cat '%s' >> '%s') >/dev/null 2>&1 &"
                                   h1 path h2 path))
        (let [deadline (+ (filestat.monotonic) 2)]
          (while (and (not= (frame.read-text path) first-half) (< (filestat.monotonic) deadline))
            (love.timer.sleep 0.001)))
        (let [caught? (= (frame.read-text path) first-half)]
          (play.load! path false)
          (note-error!)
          (let [deadline (+ (filestat.monotonic) 0.8)]
            (while (< (filestat.monotonic) deadline)
              (love.timer.sleep 0.01)
              (set state.poll-at 0)
              (play.poll-file!)
              (note-error!)))
          (let [image (do (case (play.current-plan)
                            plan (frame.render-to-canvas! state.cache canvas state.scene plan state.cam))
                          (canvas-bytes canvas))]
            (report "a file written in two halves 50 ms apart, loaded between them, shows no error and loads whole"
                    (and (= 0 (length errors)) (= state.error nil) (= image image0)))
            (print (.. "  the first load read " (if caught? "the first half only" "the whole file (the second half came first)")
                       (if (> (length errors) 0) (.. "; it showed: " (. errors 1)) ""))))
          (os.remove h1)
          (os.remove h2)
          (write! path recoloured)
          (play.poll-file! (+ (filestat.now) 0.3))))
      ;; The file replaced by a directory: said so (not 'deleted'), the scene stays.
      (os.remove path)
      (os.execute (.. "mkdir '" path "'"))
      (play.poll-file! (+ (filestat.now) 0.01))
      (play.poll-file! (+ (filestat.now) 1.5))
      (let [image5 (do (case (play.current-plan)
                         plan (frame.render-to-canvas! state.cache canvas state.scene plan state.cam))
                       (canvas-bytes canvas))]
        (report "a file replaced by a directory is reported as such and the scene keeps running"
                (and (= image5 image1) (not= nil state.message)
                     (not= nil (state.message:find "it is a directory" 1 true))))
        (print (.. "  the player says: " (tostring state.message))))
      (os.execute (.. "rmdir '" path "'")))
    (os.remove path)))

(fn run [o]
  "Run `o.cycles` reload cycles; true when every check held."
  (let [state play.state
        path (temp-scene-path)
        canvas (love.graphics.newCanvas 64 48)
        failures []
        times {:value [] :structural []}
        counts {:value 0 :structural 0 :broken 0}
        cycles o.cycles]
    (var spheres 1)
    (var shade 0.5)
    (local warm-readings [])
    (local end-readings [])
    (local window 5)
    (fn full-count []
      (collectgarbage :collect)
      (collectgarbage :collect)
      (collectgarbage :count))
    (local warm-at (math.max 30 (math.floor (/ cycles 4))))
    (var live-warm nil)
    (fn check [ok? what] (when (not ok?) (table.insert failures what)))
    (fn render! []
      (case (play.current-plan)
        plan (frame.render-to-canvas! state.cache canvas state.scene plan state.cam))
      (centre-pixel canvas))
    (fn settle! []
      ;; Two polls, the clock moved forward instead of waiting: too soon after the
      ;; write (nothing loads), then past the settle time (it loads).
      (play.poll-file! (+ (filestat.now) 0.01))
      (play.poll-file! (+ (filestat.now) 0.3)))
    (write! path (scene-text {: spheres : shade}))
    (set state.quiet? true)
    (play.start! {:scene path :frames 0})
    (set love.draw nil)
    (set love.update nil)
    (edit-check! o check)
    (play.load! path true)
    (set state.poll-at 0)
    (var before (render!))
    (for [i 1 cycles]
      (let [kind (case (% i 3) 1 :value 2 :structural 0 :broken)
            compiles state.cache.compiles
            loads state.reloads]
        (case kind
          :value (do (set shade (/ (% (* i 37) 100) 100))
                     (write! path (scene-text {: spheres : shade})))
          :structural (do (set spheres (+ 1 (% spheres structures)))
                          (write! path (scene-text {: spheres : shade})))
          :broken (write! path (broken-text i)))
        (settle!)
        (tset counts kind (+ (. counts kind) 1))
        (let [after (render!)]
          (case kind
            :value (do (check (= state.reloads (+ loads 1)) (.. "cycle " i ": value edit not reloaded"))
                       (check (= state.cache.compiles compiles) (.. "cycle " i ": value edit compiled a shader"))
                       (check (= state.error nil) (.. "cycle " i ": error after a good edit: " (tostring state.error)))
                       (check (not (same-pixel? before after)) (.. "cycle " i ": value edit did not change the image"))
                       (table.insert times.value state.last-load.ms))
            :structural (do (check (= state.reloads (+ loads 1)) (.. "cycle " i ": structural edit not reloaded"))
                            (check (= state.cache.compiles (+ compiles 1)) (.. "cycle " i ": structural edit compiled no shader"))
                            (table.insert times.structural state.last-load.ms))
            :broken (do (check (and state.error (= (state.error:find path 1 true) 1)
                                    (state.error:match "^[^:]+:%d+:"))
                               (.. "cycle " i ": broken file shows no file:line error: " (tostring state.error)))
                        (check (same-pixel? before after) (.. "cycle " i ": broken file changed the image"))))
          (set before after)))
      ;; Warm once a quarter of the run is done: the shader cache is full and the
      ;; compiler's and LÖVE's own tables have grown to their working size by then.
      ;; Two full cycles: what a finaliser (a LÖVE object's __gc) lets go is only
      ;; freed by the second, and one cycle here measured 2521 KB in a run whose
      ;; warm figure is usually 3200-3700 KB, failing the 10% check at 2829 KB.
      ;; The most of `window` readings 10 cycles apart, at warm and at the end: since
      ;; scenes of plain data are read in this process (src/scene/data.fnl), about 6 MB
      ;; of a 12 MB working set is sometimes free at a reading and sometimes not
      ;; (readings of 11920, 12052, 5961, 12173 KB in one run), so one reading at each
      ;; end failed the 10% check with no growth; a leak raises every reading.
      (when (and (>= i warm-at) (< (length warm-readings) window) (= 0 (% (- i warm-at) 10)))
        (table.insert warm-readings (full-count))
        (when (= i warm-at) (set live-warm (- state.cache.compiles state.cache.released))))
      (when (and (> i (- cycles (* 10 window))) (= 0 (% (- cycles i) 10)))
        (table.insert end-readings (full-count)))
      (when (= (% i 100) 0)
        (status.update! (string.format "soak: %d/%d reloads" i cycles))))
    (status.done!)
    (os.remove path)
    (table.insert end-readings (full-count))
    (let [memory-warm (when (> (length warm-readings) 0) (math.max (unpack warm-readings)))
          memory-end (math.max (unpack end-readings))
          live-end (- state.cache.compiles state.cache.released)]
      (print (string.format "soak: %d edits (%d value, %d structural, %d broken)"
                            cycles counts.value counts.structural counts.broken))
      (when (> (length times.value) 0)
        (print (string.format "reload time (file read, validate, plan, shader): value edit median %.1f ms, structural edit median %.1f ms; the watcher adds 0.03-0.04 s of settling"
                              (median times.value) (median times.structural))))
      (when memory-warm
        (print (string.format "Lua memory after cycle %d: %.0f KB, at the end: %.0f KB (the most of %d and %d readings)"
                              warm-at memory-warm memory-end (length warm-readings) (length end-readings)))
        (print (string.format "live shaders after cycle %d: %d, at the end: %d (%d compiled, %d released)"
                              warm-at live-warm live-end state.cache.compiles state.cache.released))
        ;; Flat means no growth beyond noise: 10% of the warm figure, and the shader
        ;; cache never holding more than it did once warm.
        (check (< memory-end (* 1.1 memory-warm)) "Lua memory grew by more than 10%")
        (check (<= live-end live-warm) "live shaders grew"))
      (each [_ f (ipairs (icollect [i f (ipairs failures)] (when (<= i 10) f)))]
        (print (.. "FAILED " f)))
      (print (string.format "soak checks: %d failed" (length failures)))
      (if (= (length failures) 0) true (values nil "soak checks failed")))))

{: run : scene-text}

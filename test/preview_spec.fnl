;; The preview of a structural edit (issue 42): while a helper compiles the new
;; shader, a thread draws the new scene with the CPU reference, small pictures first
;; (src/reference/picture.fnl, src/app/preview.fnl). Here: the pictures are the
;; reference's (pure), and in the running player (headless) an edit whose shader never
;; comes shows the new scene's previews, alone once they start
;; (`love . --edit-latency SCENE --preview-check`).

(local load (require :src.scene.load))
(local plan-mod (require :src.render.plan))
(local camera (require :src.render.camera))
(local reference (require :src.reference))
(local picture (require :src.reference.picture))

(fn bytes-of [results]
  ;; render-pixels' colours as picture's bytes.
  (table.concat (icollect [_ r (ipairs results)]
                  (let [[cr cg cb] r.color
                        b #(math.floor (+ 0.5 (* 255 (math.max 0 (math.min 1 $)))))]
                    (string.char (b cr) (b cg) (b cb) 255)))))

(local {: edit-latency-check} (require :test.support.app))

(describe "previews by the CPU reference"
  (fn []
    (it "draws a ladder of sizes, each twice the last, within the pixel budget"
      (fn []
        (assert.are.same [[16 9] [32 18] [64 36] [128 72]] (picture.ladder (/ 16 9) 9300))
        (assert.are.same [[16 9] [32 18] [64 36]] (picture.ladder (/ 16 9) 9215))
        ;; The first always, however small the budget; a tall window too.
        (assert.are.same [[9 9]] (picture.ladder 1 10))
        (assert.are.same [[5 9] [9 18]] (picture.ladder 0.5 200))))

    (each [_ file (ipairs ["scenes/gallery.fnl" "scenes/organic.fnl"])]
      (it (.. file ": a picture is the reference's one ray through each pixel's centre")
        (fn []
          (let [s (assert (load.load-file file))
                p (assert (plan-mod.scene->plan s {:view :shaded}))
                cam (camera.from-scene s)
                [w h] [16 9]
                pixels (let [ps []] (for [y 0 (- h 1)] (for [x 0 (- w 1)] (table.insert ps [x y]))) ps)
                bytes (picture.picture s p cam w h)]
            (assert.are.equal (* 4 w h) (length bytes))
            (assert.are.equal (bytes-of (reference.render-pixels s p cam w h pixels)) bytes)
            ;; Not one colour: the scene is in it.
            (var differ? false)
            (for [i 5 (* 4 w h) 4]
              (when (not= (bytes:sub i (+ i 2)) (bytes:sub 1 3)) (set differ? true)))
            (assert.is_true differ?)))))

    (it "stops between rows when asked, and gives nothing then"
      (fn []
        (let [s (assert (load.load-file "scenes/gallery.fnl"))
              p (assert (plan-mod.scene->plan s {:view :shaded}))
              cam (camera.from-scene s)]
          (var asked 0)
          (assert.is_nil (picture.picture s p cam 32 18 (fn [] (set asked (+ asked 1)) (> asked 3))))
          (assert.are.equal 4 asked))))

    (it "refuses a scene of too many objects before encoding it (a million spheres took the player to 2.1 GB)"
      (fn []
        (let [preview (require :src.app.preview)
              pv (preview.new)
              objects (fcollect [i 1 50001] {:kind :sphere :radius 0.1 :pos [i 0 0]})
              ;; Encoding it would fail: the refusal must come first.
              (id why) (preview.request! pv {: objects :render {} :unencodable (fn [])} {} {} 1)]
          (assert.is_nil id)
          (assert.truthy (why:find "more than 50000 objects" 1 true) why)
          (assert.is_nil pv.thread))))

    ;; The player, headless: a second or two each.
    (each [_ file (ipairs ["scenes/gallery.fnl" "scenes/organic.fnl"])]
      (it (.. file ": an edit whose shader never comes shows the new scene's previews, alone")
        (fn []
          (let [(verdict line) (edit-latency-check file "--preview-check" "preview check")]
            (if (= verdict :pending) (pending line) (assert.are.equal :ok verdict line))))))))

;; The compile helper's pure parts (src/app/warm.fnl): when the driver's cache is shared
;; between processes, the helper's command line, and the helper's bookkeeping with a
;; stand-in for the LÖVE thread. The whole path (a helper process, the player waiting
;; for it) runs in `love . --input-check` (test/input_spec.fnl).
(local warm (require :src.app.warm))
(local helper (require :src.app.warm-helper))

(fn env [vars] (fn [name] (. vars name)))

(describe "the compile helper"
  (fn []
    (it "trusts Mesa's and NVIDIA's on-disk caches unless they are switched off"
      (fn []
        (let [mesa "4.5 (Core Profile) Mesa 22.3.6"]
          (assert.is_true (warm.cache-shared? (env {}) mesa "Mesa"))
          (assert.is_false (warm.cache-shared? (env {:MESA_SHADER_CACHE_DISABLE "true"}) mesa "Mesa"))
          (assert.is_false (warm.cache-shared? (env {:MESA_SHADER_CACHE_DISABLE "1"}) mesa "Mesa"))
          (assert.is_false (warm.cache-shared? (env {:MESA_GLSL_CACHE_DISABLE "Yes"}) mesa "Mesa"))
          (assert.is_true (warm.cache-shared? (env {:MESA_SHADER_CACHE_DISABLE "false"}) mesa "Mesa")))
        (let [nv "3.3.0 NVIDIA 580.159.04"]
          (assert.is_true (warm.cache-shared? (env {}) nv "NVIDIA Corporation"))
          (assert.is_false (warm.cache-shared? (env {:__GL_SHADER_DISK_CACHE "0"}) nv "NVIDIA Corporation")))
        ;; Anything else: no promise that another process's compile helps.
        (assert.is_false (warm.cache-shared? (env {}) "4.6" "ATI Technologies Inc."))
        (assert.is_false (warm.cache-shared? (env {}) nil nil))))

    (it "quotes every path it puts on the helper's command line"
      (fn []
        (assert.are.equal "'a b'" (warm.shell-quote "a b"))
        (assert.are.equal "'it'\\''s; rm -rf x'" (warm.shell-quote "it's; rm -rf x"))
        (assert.are.equal
          "SDL_VIDEODRIVER=offscreen '/usr/bin/love' '/home/a b/game' --warm-server '/tmp/x$y' 4242 >/dev/null 2>&1"
          (warm.helper-command "/usr/bin/love" "/home/a b/game" "/tmp/x$y" 4242))
        ;; The background lane's helper yields the cores to the player's frames.
        (assert.are.equal
          "SDL_VIDEODRIVER=offscreen nice -n 10 '/usr/bin/love' '/g' --warm-server '/tmp/d' 7 >/dev/null 2>&1"
          (warm.helper-command "/usr/bin/love" "/g" "/tmp/d" 7 10))))

    (it "writes a job whole: under its own name only once complete"
      (fn []
        (let [dir (.. (os.tmpname) ".d")
              path (warm.job-path dir 7 :glsl)]
          (os.execute (.. "mkdir " dir))
          (assert.are.equal (.. dir "/job-7.glsl") path)
          (assert.is_true (warm.write-whole! path "void main() {}"))
          (assert.are.equal "void main() {}" (with-open [f (io.open path)] (f:read :*a)))
          (assert.is_nil (io.open (.. path ".part")))
          (os.remove path)
          (os.remove dir)
          (assert.is_nil (warm.write-whole! (.. dir "/gone/job-1.glsl") "x")))))

    (it "runs one helper at a time, the newest request waiting, and settles each key once"
      (fn []
        ;; A stand-in for start!'s thread: jobs finish when the test says so.
        (let [started []
              w {:enabled? true :settled {} :settled-count 0 :failures 0 :running nil :queued nil
                 :start! (fn [w key _source]
                           (table.insert started key)
                           (set w.running {: key :check #(. {true :done false :failed}
                                                            (?. w.outcome key))})
                           true)
                 :outcome {}}]
          (assert.is_false (warm.ready? w :a #"A"))
          (assert.are.equal :running (warm.status w :a))
          (assert.is_false (warm.ready? w :b #"B"))
          (assert.is_false (warm.ready? w :c #"C"))   ; c replaces b in the queue
          (assert.are.equal :queued (warm.status w :c))
          (assert.are.equal nil (warm.status w :b))
          (assert.are.same [:a] started)
          (tset w.outcome :a true)
          (warm.poll! w)
          (assert.are.equal :done (warm.status w :a))
          (assert.is_true (warm.ready? w :a #"A"))
          (assert.are.same [:a :c] started)
          (tset w.outcome :c false)
          (warm.poll! w)
          (assert.are.equal :failed (warm.status w :c))
          ;; A failed helper leaves the compile to the player: ready.
          (assert.is_true (warm.ready? w :c #"C"))
          ;; A shader that cannot be generated needs no helper: the player reports it.
          (assert.is_true (warm.ready? w :d #(values nil "no shader")))
          (assert.are.same [:a :c] started))))

    (it "lets an edit overtake the background lane: its waiting job dropped, its job at work cancelled"
      (fn []
        ;; Issue 42: the still's shader takes 3 to 30 s in a helper; an edit made
        ;; meanwhile waited for it. Stand-in jobs finish when the test says so.
        (let [started []
              w {:enabled? true :settled {} :settled-count 0 :failures 0 :cancelled 0
                 :background {}
                 :start! (fn [lane key _source]
                           (table.insert started key)
                           (set lane.running {: key :check #(. {true :done false :failed}
                                                               (?. lane.outcome key))})
                           (set lane.outcome {})
                           true)}]
          ;; The folded shader at work in the background, the still's waiting behind it.
          (assert.is_false (warm.ready? w :folded #"F" true))
          (assert.is_false (warm.ready? w :still #"S" true))
          (assert.are.equal :running (warm.status w :folded))
          (assert.are.equal :queued (warm.status w :still))
          (assert.are.same [:folded] started)
          ;; The edit starts at once, in its own lane; the background is cancelled
          ;; (unsettled: asked for again if it is wanted again).
          (assert.is_false (warm.ready? w :edit #"E"))
          (assert.are.same [:folded :edit] started)
          (assert.are.equal :running (warm.status w :edit))
          (assert.are.equal nil (warm.status w :folded))
          (assert.are.equal nil (warm.status w :still))
          (assert.are.equal 1 w.cancelled)
          (assert.is_nil w.background.running)
          ;; Asking again for a job at work cancels nothing (the player asks every frame).
          (assert.is_false (warm.ready? w :later-background #"L" true))
          (assert.is_false (warm.ready? w :edit #"E"))
          (assert.are.equal :running (warm.status w :later-background))
          (tset w.outcome :edit true)
          (warm.poll! w)
          (assert.are.equal :done (warm.status w :edit))
          (assert.is_true (warm.ready? w :edit #"E"))
          (assert.are.equal 1 w.cancelled)
          ;; Background requests never cancel an edit.
          (assert.is_false (warm.ready? w :edit2 #"E2"))
          (assert.are.equal 2 w.cancelled)
          (assert.is_false (warm.ready? w :bg2 #"B2" true))
          (assert.are.equal :running (warm.status w :edit2))
          (assert.are.equal :running (warm.status w :bg2)))))

    (it "hands the helper the player's texture sizes in lines it removes again"
      (fn []
        (let [source "//warm-texture uFieldCells 1024 22\n//warm-texture uFieldObjects 1024 30\nvoid main() {}\n// a comment\n"]
          (assert.are.same [["uFieldCells" 1024 22] ["uFieldObjects" 1024 30]] (helper.textures source))
          (assert.are.equal "void main() {}\n// a comment\n" (helper.shader-text source))
          (assert.are.same [] (helper.textures "void main() {}\n"))
          (assert.are.equal "/tmp/d" (helper.arg-after ["x" "--warm-server" "/tmp/d" "12"] "--warm-server"))
          (assert.are.equal "12" (helper.arg-after ["x" "--warm-server" "/tmp/d" "12"] "--warm-server" 2)))))

    (it "stops asking for helpers after three failures in a row"
      (fn []
        (let [w {:enabled? true :settled {} :settled-count 0 :failures 0
                 :start! (fn [w key _source]
                           (set w.running {: key :check #:failed})
                           true)}]
          (each [_ key (ipairs [:a :b :c])]
            (assert.is_true w.enabled?)
            (assert.is_false (warm.ready? w key #"S"))
            (warm.poll! w))
          (assert.is_false w.enabled?)
          (assert.is_true w.gave-up?)
          (assert.is_true (warm.ready? w :d #(error "not asked"))))))

    (it "leaves everything to the player when it is off"
      (fn []
        (assert.is_true (warm.ready? {:enabled? false} :a #(error "not asked")))))))

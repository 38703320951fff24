;; The accuracy-against-run-time report (src/verify/report.fnl, tools/report.fnl): the Pareto
;; front, the pieces the sweep is built from, and a quick end-to-end run.

(local report (require :src.verify.report))
(local reference (require :src.reference))
(local png (require :src.util.png))
(local headless (require :src.backend.headless))
(local {: sh} (require :test.support.app))

(fn row [name ms err ?gpu]
  {:name name :ms ms :error err :gpu-error ?gpu})

(fn names-at [rows indices]
  (icollect [_ i (ipairs indices)] (. rows i :name)))

(describe "report.pareto-front"
  (fn []
    (it "keeps the rows no other row beats in both time and error"
      (fn []
        (let [rows [(row :a 10 5) (row :b 20 1) (row :c 15 6) (row :d 5 9) (row :e 30 1)]]
          ;; c: a is faster and more accurate; e: b is as accurate and faster.
          (assert.are.same [:a :b :d] (names-at rows (report.pareto-front rows))))))

    (it "keeps rows tied in both measures and drops rows equal in one and worse in the other"
      (fn []
        (let [rows [(row :a 10 2) (row :b 10 2) (row :c 10 3) (row :d 12 2)]]
          (assert.are.same [:a :b] (names-at rows (report.pareto-front rows))))))

    (it "handles one row, no rows, and rows without numbers"
      (fn []
        (assert.are.same [1] (report.pareto-front [(row :a 1 1)]))
        (assert.are.same [] (report.pareto-front []))
        (let [rows [(row :a nil 1) (row :b 5 2) (row :c 4 nil)]]
          (assert.are.same [:b] (names-at rows (report.pareto-front rows))))))

    (it "uses the keys it is given"
      (fn []
        (let [rows [(row :a 10 1 9) (row :b 20 0.5 1) (row :c 30 0.1 0.5)]]
          (assert.are.same [:a :b :c] (names-at rows (report.pareto-front rows)))
          (assert.are.same [:a :b :c] (names-at rows (report.pareto-front rows :ms :gpu-error)))
          (set (. rows 3 :gpu-error) 2)
          (assert.are.same [:a :b] (names-at rows (report.pareto-front rows :ms :gpu-error))))))

    (it "returns a front where no member dominates another, on random data"
      (fn []
        (var state 12345)
        (let [random (fn [] (set state (% (* state 16807) 2147483647)) (/ state 2147483647))
              rows (fcollect [i 1 200] (row i (math.floor (* 50 (random))) (math.floor (* 50 (random)))))
              front (report.pareto-front rows)
              on {}]
          (each [_ i (ipairs front)] (tset on i true))
          (each [i a (ipairs rows)]
            (let [beaten? (accumulate [hit false j b (ipairs rows)]
                            (or hit (and (not= i j) (<= b.ms a.ms) (<= b.error a.error)
                                         (or (< b.ms a.ms) (< b.error a.error)))))]
              (assert.are.equal (not beaten?) (not (not (. on i)))))))))))

(describe "report helpers"
  (fn []
    (it "decodes the heat view's colours back into steps / max-steps"
      (fn []
        (for [k 0 400]
          (let [h (/ k 400)
                (r g b) (reference.heat-color h)]
            (assert.is_true (< (math.abs (- h (report.heat->fraction r g b))) 1e-9)
                            (.. "h = " h))))))

    (it "applies overrides, drops unknown keys asking for the article's value, and validates"
      (fn []
        (let [base {:max-steps 500 :epsilon 1e-4}
              known {:max-steps true :epsilon true}]
          (assert.are.same {:max-steps 64 :epsilon 1e-4}
                           (report.apply-setting base {:max-steps 64} known))
          (assert.are.same {:max-steps 500 :epsilon 1e-4}
                           (report.apply-setting base {:normals :one-sided} known))
          (let [(r why) (report.apply-setting base {:normals :tetrahedron} known)]
            (assert.is_nil r)
            (assert.is_truthy (why:find "normals")))
          (let [(r why) (report.apply-setting base {:max-steps -3} known)]
            (assert.is_nil r)
            (assert.is_truthy (why:find "max%-steps"))))))

    (it "sweeps one axis at a time around the scene's settings"
      (fn []
        (let [settings (report.sweep-settings {:max-steps 500 :epsilon 1e-4 :reflections 2} false)
              names (collect [_ s (ipairs settings)] s.name s)]
          (assert.is_truthy names.base)
          (assert.is_truthy names.article)
          (assert.is_truthy names.ms64)
          (assert.is_truthy names.refl0)
          (assert.is_truthy names.refl1)
          (assert.is_nil names.refl2)
          (each [_ s (ipairs settings)]
            (when (and (not= s.axis :combined) (not= s.axis :reference) (not= s.axis :base)
                       (not= s.axis :hit-test))
              (assert.are.equal 1 (accumulate [n 0 _ (pairs s.overrides)] (+ n 1))))))))

    (it "fills the defaults from the scene loader"
      (fn []
        (let [d (report.defaults-overrides {:max-steps 99})]
          (assert.are.equal 99 d.max-steps)
          (assert.is_number d.epsilon))))

    (it "states the article's and the defaults' figures for the seed scene"
      (fn []
        (let [mk (fn [name ms err]
                   {:name name :ms ms :error err :aliases [] :steps 10
                    :cpu {:mean err :max 9 :over-share 0.1 :hit-miss 1 :count 100}
                    :gpu {:mean err :max 9 :over-share 0.1 :hit-miss 2}})
              result {:defaults {:max-steps 128}
                      :scenes [{:name "seed" :width 32 :height 18
                                :rows [(mk "article" 20 1.5) (mk "defaults" 10 1.25)]}]}
              (text data) (report.defaults-statement result)]
          (assert.is_truthy (text:find "20.0 ms/frame" 1 true))
          (assert.is_truthy (text:find "10.0 ms/frame" 1 true))
          (assert.is_truthy (text:find "2.00x" 1 true))
          (assert.are.equal 2 data.speedup)
          (assert.is_nil (report.defaults-statement result "nope")))))))

(fn read-all [path]
  (case (io.open path :rb)
    f (let [t (f:read :*a)] (f:close) t)))

(fn gnuplot? []
  (= 0 (sh "command -v gnuplot")))

(describe "the quick report"
  (fn []
    (let [(ctx why) (headless.context)]
      (if (not ctx)
          (it "needs OSMesa" (fn [] (pending (.. "OSMesa is not available: " (tostring why)))))
          (let [dir "test/out/report-quick"
                state {}
                run! (fn []
                       (when (= nil state.output)
                         (os.execute (.. "rm -rf " dir))
                         (let [(code out) (sh (.. "luajit tools/fnl.lua tools/report.fnl --quick --out " dir))]
                           (set state.code code)
                           (set state.output out)
                           (set state.markdown (read-all (.. dir "/report.md")))))
                       state)]
            (it "runs and writes a table of numbers per scene"
              (fn []
                (let [{: code : output : markdown} (run!)]
                  (assert.are.equal 0 code output)
                  (assert.is_truthy markdown (.. "no report.md; output:\n" output))
                  (let [scenes (icollect [name (markdown:gmatch "\n## ([%w%-_]+) %(")] name)]
                    (assert.is_true (>= (length scenes) 1) markdown)
                    (each [_ name (ipairs scenes)]
                      (let [at (markdown:find (.. "\n## " name " (") 1 true)
                            section (markdown:sub at (or (markdown:find "\n## " (+ at 1) true) -1))
                            rows (icollect [line (section:gmatch "\n(|[^\n]+|)")]
                                   (when (line:match "^| [^|]*| [^|]*%w[^|]*| [^|]*| [%d.]+ | [%d.]+ | [%d.]+ |")
                                     line))]
                        (assert.is_truthy (section:find "| front | setting |" 1 true) section)
                        (assert.is_true (>= (length rows) 3) section)
                        ;; At least one row is on the front.
                        (assert.is_truthy (section:find "| cpu" 1 true) section))))
                  (assert.is_truthy (markdown:find "## Summary" 1 true))
                  (assert.is_truthy (markdown:find "Scene seed" 1 true)))))

            (it "draws a plot per scene that decodes as a PNG"
              (fn []
                (if (not (gnuplot?))
                    (pending "gnuplot is not installed (apt-get install gnuplot-nox)")
                    (let [{: markdown} (run!)]
                      (each [name (markdown:gmatch "%(([%w%-_]+%.png)%)")]
                        (let [(image err) (png.read-file (.. dir "/" name))]
                          (assert.is_truthy image err)
                          (assert.is_true (> image.width 400))
                          (assert.is_true (> image.height 200))))
                      (assert.is_truthy (png.read-file (.. dir "/seed.png"))))))))))))

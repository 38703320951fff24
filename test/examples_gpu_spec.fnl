;; The example scenes of test/examples_spec.fnl (issue 44) on the GPU: OSMesa's picture
;; of each generated shader against the CPU reference marcher's, as
;; test/vectors_gpu_spec.fnl checks the first three examples; the distance the GPU
;; computes (`love . --probe SCENE --gpu`) against the CPU's at points about each
;; custom node; and the Mandelbulb's heat view through the app's --render, where no
;; pixel may show a ray that ran out of steps.
(local headless (require :src.backend.headless))
(local load (require :src.scene.load))
(local png (require :src.util.png))
(local app (require :test.support.app))
(local {: lcg} (require :test.support.fields))
(local {: prepare : gpu-render : compare-image : passes? : describe-failures : report-line}
       (require :test.support.gpu-check))

(local files ["examples/mandelbulb.fnl" "examples/mandelbox.fnl" "examples/gyroid-shell.fnl" "examples/pillar-grid.fnl"
              "examples/smooth-blend.fnl" "examples/pebble-cairn.fnl" "examples/twisted-box.fnl"
              "examples/chain-links.fnl"])

;; test/vectors_gpu_spec.fnl's budgets (test/gpu_vs_cpu_spec.fnl's for
;; scenes/custom.fnl): at most two sampled pixels more than 2/255 apart (a grazing
;; reflection or shadow edge), none past 40; the normals view at most one, by 3.
(local budgets {:shaded {:over 2 :max 40} :normals {:over 1 :max 3}})
;; test/support/gpu-check.fnl's size, as test/vectors_gpu_spec.fnl's: the sampled
;; pixels (a 16 x 16 grid and up to 256 beside edges) do not depend on it, their
;; places do. (At 128 x 96 one normals pixel of the Mandelbulb's differs by 4.1, a
;; crease where float32 and doubles stop a ray on either side.)
(local size [256 224])

(local points-per-node 1000)

(fn write-file [path text]
  (with-open [f (assert (io.open path :wb))] (f:write text)))

(fn probe-points [file]
  "Points about each custom node of `file`: its bounds grown by half around its
position (a node's turn aside), `points-per-node` each, as the text --probe reads."
  (let [scene (assert (load.load-file file))
        rand (lcg 45)
        lines []]
    (each [_ o (ipairs scene.objects)]
      (when (?. o :tree :custom)
        (let [[px py pz] (or o.tree.pos [0 0 0])
              [hx hy hz] o.tree.bounds]
          (for [_ 1 points-per-node]
            (table.insert lines (string.format "%.9f %.9f %.9f"
                                               (+ px (* 1.5 hx (- (* 2 (rand)) 1)))
                                               (+ py (* 1.5 hy (- (* 2 (rand)) 1)))
                                               (+ pz (* 1.5 hz (- (* 2 (rand)) 1)))))))))
    (.. (table.concat lines "\n") "\n")))

(fn probe [file points-path gpu?]
  "The scene distance at each point of `points-path`, from the CPU evaluator or the
generated GLSL: the first number of each line `love . --probe` prints."
  (let [(code out) (app.love (.. "--probe " file (if gpu? " --gpu" "") " < " points-path))]
    (assert.are.equal 0 code out)
    (icollect [line (out:gmatch "[^\n]+")] (tonumber (line:match "^(%S+)")))))

(fn heat-out-of-steps [file out]
  "Render `file`'s heat view through the app at 96 x 72, one ray a pixel, into
`out`: the pixels whose ray took 98% of the step budget or more (heat.glsl's colour
at h = 0.98 to 1 is red 0.58 to 0.5, green and blue 0), and the picture."
  (let [(code text) (app.love (.. "--render " file " --out " out " --size 96x72 --samples 1 --view heat"))
        _ (assert.are.equal 0 code text)
        img (assert (png.read-file out))]
    (var n 0)
    ;; The pixels are an FFI array of RGBA bytes from 0.
    (for [i 0 (- (* img.width img.height) 1)]
      (let [k (* 4 i)
            r (. img.pixels k) g (. img.pixels (+ k 1)) b (. img.pixels (+ k 2))]
        (when (and (<= 125 r 150) (<= g 1) (<= b 1))
          (set n (+ n 1)))))
    (values n img)))

(describe "the example scenes of examples/ on the GPU"
  (fn []
    (os.execute "mkdir -p test/out")
    (let [(ctx why) (headless.context)]
      (if (not ctx)
          (pending (.. "OSMesa is not available: " (tostring why)))
          (each [_ file (ipairs files)]
            (it (.. file ": the GPU picture matches the CPU reference, shaded and normals")
              (fn []
                (each [_ view (ipairs [:shaded :normals])]
                  (let [budget (. budgets view)
                        prepared (prepare file {: view : size})
                        st (compare-image prepared (gpu-render ctx prepared))
                        label (.. file " " view)]
                    (print (report-line label st))
                    (assert.is_true (>= st.count 256) (.. label ": only " st.count " pixels sampled"))
                    (assert.is_true (passes? st budget) (describe-failures label st budget))))))))

      (each [_ file (ipairs files)]
        (it (.. file ": the GPU's distance is the CPU's within 2e-3 at " points-per-node " points a node")
          (fn []
            (let [points-path "test/out/examples-probe.txt"
                  _ (write-file points-path (probe-points file))
                  cpu (probe file points-path false)
                  gpu (probe file points-path true)]
              (assert.are.equal (length cpu) (length gpu))
              (assert.is_true (>= (length cpu) points-per-node))
              (var worst {:err 0})
              (each [i c (ipairs cpu)]
                (let [g (. gpu i)
                      ;; Relative to 1 + |d|: float32 keeps 6e-8 of values of order
                      ;; 1, a few operations' roundings each; the Mandelbulb's orbit
                      ;; multiplies them by up to 8 r^7 a turn inside the bulb,
                      ;; where its estimate, tiny, counts for no ray. 2e-3 is the
                      ;; issue's bound for a picture's worth of agreement.
                      err (/ (math.abs (- c g)) (+ 1 (math.abs c)))]
                  (when (> err worst.err) (set worst {: err : i :cpu c :gpu g}))))
              (print (string.format "examples: %s probe: %d points, largest GPU-CPU difference %.3g of 1 + |d| (point %s: cpu %s gpu %s)"
                                    file (length cpu) worst.err (tostring worst.i)
                                    (tostring worst.cpu) (tostring worst.gpu)))
              (assert.is_true (<= worst.err 2e-3)
                              (string.format "point %s: cpu %s gpu %s" (tostring worst.i)
                                             (tostring worst.cpu) (tostring worst.gpu)))))))

      (it "examples/mandelbulb.fnl draws whole on the GPU: no pixel of the heat view ran out of steps"
        (fn []
          (let [(n img) (heat-out-of-steps "examples/mandelbulb.fnl" "test/out/examples-mandelbulb-heat.png")]
            (print (string.format "examples: mandelbulb heat view %dx%d: %d pixels at 98%% of the steps or more"
                                  img.width img.height n))
            (assert.are.equal 0 n))))

      (it "an example renders from another directory (love PROJECT --render examples/NAME.fnl)"
        (fn []
          ;; A scene path not found under the working directory is read from the
          ;; project's own files (src/util/files.fnl's read-user): an empty folder
          ;; of its own, so no examples/ there shadows the project's.
          (let [out (.. app.root "/test/out/examples-elsewhere.png")
                _ (os.remove out)
                (code text) (app.sh (.. "d=$(mktemp -d); (cd \"$d\" && SDL_VIDEODRIVER=offscreen timeout "
                                        app.hang-seconds " love " app.root
                                        " --render examples/pebble-cairn.fnl --out " out
                                        " --size 64x48 --samples 1); c=$?; rmdir \"$d\"; (exit $c)"))
                img (png.read-file out)]
            (assert.are.equal 0 code text)
            (assert.truthy img text)
            (assert.are.same [64 48] [img.width img.height]))))

      (it "the heat check sees rays out of steps: the Mandelbulb with a factor of 600 declared"
        (fn []
          ;; The check itself: each step divided by 600 (declared and trusted, so
          ;; whatever the loader measures), the rays about the bulb run out of steps.
          ;; The factor the loader uses today, 548 (1.1 times the 498 it measures), does alike: test/examples_spec.fnl
          ;; counts 377 of 3072 CPU reference rays out of steps with it.
          (let [text (with-open [f (assert (io.open "examples/mandelbulb.fnl"))] (f:read :*a))
                (slow k) (text:gsub ":lipschitz 1 :trust%-lipschitz true" ":lipschitz 600 :trust-lipschitz true")
                file "test/out/examples-mandelbulb-slow.fnl"
                _ (write-file file slow)
                (n img) (heat-out-of-steps file "test/out/examples-mandelbulb-slow-heat.png")]
            (print (string.format "examples: mandelbulb, factor 600, heat view: %d of %d pixels out of steps"
                                  n (* img.width img.height)))
            (assert.are.equal 1 k)
            (assert.is_true (> n 100) (.. n " pixels out of steps"))))))))

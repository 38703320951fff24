;; `love . --mesh` (issue 31) run headless through the app's command line: the CPU
;; evaluator and the GPU (llvmpipe in CI) write closed meshes of a scene, progress
;; goes to stderr, and bad arguments and scenes are refused with a clear message.

(local formats (require :src.mesh.formats))
(local check (require :src.mesh.check))
(local load (require :src.scene.load))
(local mesh-scene (require :src.mesh.scene))
(local contour (require :src.mesh.contour))

(fn run [args]
  "Run `love . ARGS` headless: exit code, stdout, stderr."
  (let [err-path (os.tmpname)
        text (with-open [p (io.popen (.. "SDL_VIDEODRIVER=offscreen timeout 300 love . " args
                                         " 2>" err-path "; echo \"exit:$?\""))]
               (p:read :*a))
        err (with-open [f (io.open err-path :rb)] (f:read :*a))
        code (tonumber (text:match "exit:(%d+)%s*$"))]
    (os.remove err-path)
    (values code (pick-values 1 (text:gsub "exit:%d+%s*$" "")) err)))

(fn read-mesh [path]
  (let [bytes (with-open [f (assert (io.open path :rb))] (f:read :*a))]
    (assert (formats.decode bytes (formats.format-of path)))))

(describe "love . --mesh"
  (fn []
    (os.execute "mkdir -p test/out")
    (local scene-path "scenes/machined-part.fnl")
    (local scene (assert (load.load-file scene-path)))
    (local volumes {})
    (local counts {})

    (each [_ [label flag path] (ipairs [["the CPU evaluator" "" "test/out/mesh-machined.ply"]
                                        ["the GPU" " --gpu" "test/out/mesh-machined-gpu.ply"]])]
      (it (.. "writes a closed coloured mesh of a scene's finite objects with " label)
        (fn []
          (os.remove path)
          (let [(code out err) (run (.. "--mesh " scene-path " --out " path " --resolution 48" flag))]
            (assert.are.equal 0 code err)
            (assert.truthy (out:find (.. "wrote " path ": ") 1 true) out)
            (assert.truthy (out:find "left out objects[1] (plane): infinite" 1 true) out)
            ;; Progress: each phase, with the time left once the blocks are known.
            (assert.truthy (err:find "mesh: corners, [^\n]* left\n") err)
            (let [m (read-mesh path)
                  t (check.topology m)
                  selection (assert (mesh-scene.select-objects scene))
                  grid (mesh-scene.grid-for selection 48)
                  field (assert (mesh-scene.cpu-field selection.scene))
                  worst (check.surface-distance
                         m (fn [x y z] (math.max (field.distance x y z)
                                                 (contour.box-distance grid.cut x y z))))]
              (assert.is_true t.manifold? (check.describe t))
              (assert.is_truthy m.colors)
              ;; float32 positions and (on the GPU) distances: still within half a cell.
              (assert.is_true (<= worst (* 0.5 grid.h)) (tostring (/ worst grid.h)))
              (table.insert volumes (check.volume m))
              (table.insert counts t.triangles))))))

    (it "gives the same volume on the GPU as on the CPU, within 0.5%"
      (fn []
        ;; float32 sampling moves crossings by far less than a cell.
        (assert.are.equal 2 (length volumes))
        (let [[a b] volumes]
          (assert.is_true (< (math.abs (- a b)) (* 0.005 a)) (.. a " " b)))))

    (it "makes as many triangles on the GPU as on the CPU"
      (fn []
        ;; Both classify a grid point by the same rule, d below minus a thousandth
        ;; of a cell (src/mesh/scene.fnl's surface-offset): a face on a grid plane
        ;; (machined-part's base, platonic-shelf's boards at the region's bounds)
        ;; has d = 0 there up to rounding, double on one and float32 on the other.
        ;; Before: machined-part at 48 5572 and 5524, platonic-shelf at 32 1552 and
        ;; 1420.
        (assert.are.equal 2 (length counts))
        (assert.are.equal (. counts 1) (. counts 2))
        (let [shelf (icollect [_ flag (ipairs ["" " --gpu"])]
                      (let [path (.. "test/out/mesh-shelf" (if (= flag "") "" "-gpu") ".stl")
                            (code out err) (run (.. "--mesh scenes/platonic-shelf.fnl --out " path
                                                    " --resolution 32" flag))]
                        (assert.are.equal 0 code err)
                        (tonumber (out:match ": (%d+) triangles"))))]
          (assert.are.equal (. shelf 1) (. shelf 2)))))

    (it "writes an adaptive mesh with --adaptive, and says how many triangles it kept"
      (fn []
        (let [path "test/out/mesh-adaptive.ply"
              ;; A quarter of a cell at 48 (0.19): 1,734 of 5,388 triangles kept.
              (code out err) (run (.. "--mesh scenes/machined-part.fnl --out " path
                                      " --resolution 48 --adaptive 0.05"))
              kept (tonumber (out:match "adaptive within 0.05: (%d+) of the grid's"))
              grid (tonumber (out:match "of the grid's (%d+) triangles"))]
          (assert.are.equal 0 code err)
          (assert.truthy (err:find "mesh: simplify, " 1 true) err)
          (assert.is_true (< kept (* 0.5 grid)) out)
          (let [m (read-mesh path)]
            (assert.are.equal kept (/ (length m.triangles) 3))
            (assert.is_true (. (check.topology m) :manifold?))
            (assert.is_truthy m.colors)))))

    (it "cuts a ground plane by a given region, and says so"
      (fn []
        (let [path "test/out/mesh-region.stl"
              (code out err) (run (.. "--mesh scenes/seed.fnl --out " path
                                      " --resolution 24 --region -10,-10,-1,10,10,6"))]
          (assert.are.equal 0 code err)
          ;; objects[5]'s box only touches the region's face y = -10: nothing of it is inside.
          (assert.truthy (out:find "cut by the region: objects[3] (box), objects[6] (plane); left out, outside the region: objects[5] (sphere)" 1 true) out)
          (assert.is_true (. (check.topology (read-mesh path)) :manifold?)))))

    (it "meshes a box under a region of 1e30 as under its own bounds (the region clipped)"
      (fn []
        ;; The grid was the region's: 12 triangles in a cell of 1.6e28 at 128, and at
        ;; 512 a table overflow after 4.2 GB.
        (let [scene-file "test/out/mesh-finite.fnl"
              own-path "test/out/mesh-own.stl"
              huge-path "test/out/mesh-huge-region.stl"
              _ (with-open [f (io.open scene-file :w)]
                  (f:write "{:objects [{:kind :box :size [4 4 4] :pos [0 0 2]}\n"
                           "           {:kind :sphere :radius 1.5 :pos [-4 -2 1.5]}]}\n"))
              (c1 out1 err1) (run (.. "--mesh " scene-file " --out " own-path " --resolution 24"))
              (c2 out2 err2) (run (.. "--mesh " scene-file " --out " huge-path " --resolution 24"
                                      " --region -1e30,-1e30,-1e30,1e30,1e30,1e30"))]
          (assert.are.equal 0 c1 err1)
          (assert.are.equal 0 c2 err2)
          (assert.truthy (out2:find "every object lies within the region; the grid spans -5.5,-3.5,0,2,2,4, the region clipped to the objects' box" 1 true) out2)
          (let [count (fn [out] (tonumber (out:match ": (%d+) triangles")))
                grid (fn [out] (out:match "%(%d+x%d+x%d+ grid%)"))]
            (assert.are.equal (count out1) (count out2))
            (assert.are.equal (grid out1) (grid out2))
            (assert.are.same (. (read-mesh own-path) :positions)
                             (. (read-mesh huge-path) :positions))))))

    (it "refuses bad arguments and scenes with a clear message"
      (fn []
        (each [_ [args message]
               (ipairs [["--mesh scenes/seed.fnl --out x.off"
                         "error: --out must name a .stl, .ply or .obj file, got x.off"]
                        ["--mesh scenes/seed.fnl" "error: --mesh needs --out FILE.stl, FILE.ply or FILE.obj"]
                        ["--mesh scenes/seed.fnl --out x.stl --resolution 2000"
                         "error: --resolution must be a whole number from 8 to 1024, got 2000"]
                        ["--mesh scenes/seed.fnl --out x.stl --region 1,2,3"
                         "error: --region must be six numbers x0,y0,z0,x1,y1,z1, got 1,2,3"]
                        ["--mesh scenes/seed.fnl --out x.stl --resolution 1e999"
                         "error: --resolution must be a whole number from 8 to 1024, got 1e999"]
                        ["--mesh scenes/seed.fnl --out x.stl --region 0,0,0,1,1,nan"
                         "error: --region must be six numbers x0,y0,z0,x1,y1,z1, got 0,0,0,1,1,nan"]
                        ["--mesh scenes/seed.fnl --out x.stl --region 0,0,0,1,1,1e400"
                         "error: --region must be six numbers x0,y0,z0,x1,y1,z1, got 0,0,0,1,1,1e400"]
                        ["--mesh scenes/seed.fnl --out x.stl --region 0,0,0,1,0,1"
                         "error: --region: y1 must be greater than y0, got 0,0,0,1,0,1"]
                        ["--mesh scenes/seed.fnl --out x.stl --region 0,0,3,1,1,-3"
                         "error: --region: z1 must be greater than z0, got 0,0,3,1,1,-3"]
                        ["--mesh scenes/seed.fnl --out test/out/x.stl --region 1e29,1e29,1e29,1e30,1e30,1e30"
                         "(is the region clear of every object?)"]
                        ["--render scenes/seed.fnl --out x.png --resolution 64"
                         "error: --resolution only goes with --mesh"]
                        ["--render scenes/seed.fnl --out x.png --adaptive 0.1"
                         "error: --adaptive only goes with --mesh"]
                        ["--mesh scenes/seed.fnl --out x.stl --adaptive 0"
                         "error: --adaptive must be a distance above 0 in the scene's units"]
                        ["--mesh scenes/seed.fnl --out /nonexistent-folder/x.stl"
                         "error: --out /nonexistent-folder/x.stl: "]
                        ["--mesh test/fixtures/mesh-plane-only.fnl --out test/out/x.stl"
                         "error: test/fixtures/mesh-plane-only.fnl: the scene has no finite objects to mesh (objects[1] (plane) infinite); give --region x0,y0,z0,x1,y1,z1 to mesh them cut by a box"]])]
          (let [(code _ err) (run args)]
            (assert.are.equal 1 code args)
            (assert.truthy (err:find message 1 true) err)))))))

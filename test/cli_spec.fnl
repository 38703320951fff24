;; tier: fast
;; Specs for src/app/cli.fnl: every mode, the defaults, and the error for each bad argument.
(local cli (require :src.app.cli))

(fn parse-error [args]
  (let [(o err) (cli.parse args)]
    (assert.is_nil o)
    (assert.are.equal :string (type err))
    err))

(describe "cli: modes"
  (fn []
    (it "plays the seed scene by default"
      (fn []
        (assert.are.same {:mode :play :scene "scenes/seed.fnl" :frames 5 :cycles 300} (cli.parse []))
        (assert.are.equal "scenes/seed.fnl" cli.default-scene)))

    (it "parses --help and -h, and refuses any other single-dash word"
      (fn []
        (assert.are.equal :help (. (cli.parse ["--help"]) :mode))
        (assert.are.equal :help (. (cli.parse ["-h"]) :mode))
        (let [(o err) (cli.parse ["-x"])]
          (assert.is_nil o)
          (assert.are.equal "unknown option -x" err))))

    (it "parses --target-fps for playing (the frame rate held while moving) and --input-check"
      (fn []
        (assert.are.equal 15 (. (cli.parse ["a.fnl" "--target-fps" "15"]) :target-fps))
        (assert.are.same [nil "--target-fps only goes with playing a scene"]
                         [(cli.parse ["--render" "a.fnl" "--out" "a.png" "--target-fps" "15"])])
        (assert.are.same [nil "--target-fps must be at most 240, got 500"]
                         [(cli.parse ["--target-fps" "500"])])
        (assert.are.same [nil "--target-fps must be a whole number >= 1, got 0.5"]
                         [(cli.parse ["--target-fps" "0.5"])])
        (assert.are.equal :input-check (. (cli.parse ["--input-check"]) :mode))))

    (it "parses --sync-compile for playing only (no compile helper)"
      (fn []
        (assert.is_true (. (cli.parse ["a.fnl" "--sync-compile"]) :sync-compile?))
        (assert.is_true (. (cli.parse ["--edit-latency" "a.fnl" "--sync-compile"]) :sync-compile?))
        (assert.are.same [nil "--sync-compile only goes with playing a scene or --edit-latency"]
                         [(cli.parse ["--render" "a.fnl" "--out" "a.png" "--sync-compile"])])))

    (it "parses the scene-tree modes: --probe (with --gpu), --tree, --kinds"
      (fn []
        (assert.are.same {:mode :probe :scene "a.fnl" :gpu? true :frames 5 :cycles 300}
                         (cli.parse ["--probe" "a.fnl" "--gpu"]))
        (assert.are.same {:mode :tree :scene "a.fnl" :frames 5 :cycles 300}
                         (cli.parse ["--tree" "a.fnl"]))
        (assert.are.equal :kinds (. (cli.parse ["--kinds"]) :mode))
        (let [(o err) (cli.parse ["--tree" "a.fnl" "--gpu"])]
          (assert.is_nil o)
          (assert.are.equal "--gpu only goes with --probe or --mesh" err))))

    (it "parses --export-shader, which writes a .glsl file"
      (fn []
        (assert.are.same {:mode :export-shader :scene "a.fnl" :out "a.glsl" :frames 5 :cycles 300}
                         (cli.parse ["--export-shader" "a.fnl" "--out" "a.glsl"]))
        (assert.are.equal "--export-shader needs --out FILE.glsl"
                          (select 2 (cli.parse ["--export-shader" "a.fnl"])))
        (assert.are.equal "--out must name a .glsl file, got a.png"
                          (select 2 (cli.parse ["--export-shader" "a.fnl" "--out" "a.png"])))))

    (it "parses --record with --out DIR, --frames, --fps, --size and --turntable"
      (fn []
        (assert.are.same {:mode :record :scene "a.fnl" :out "frames" :frames 12 :fps 24
                          :size [64 48] :turntable? true :cycles 300}
                         (cli.parse ["--record" "a.fnl" "--out" "frames" "--frames" "12" "--fps" "24"
                                     "--size" "64x48" "--turntable"]))
        (assert.are.equal "--record needs --out DIR" (select 2 (cli.parse ["--record" "a.fnl"])))
        (assert.are.equal "--turntable only goes with --record"
                          (select 2 (cli.parse ["--render" "a.fnl" "--out" "a.png" "--turntable"])))
        (assert.are.equal "--fps must be a whole number >= 1, got 0"
                          (select 2 (cli.parse ["--record" "a.fnl" "--out" "d" "--fps" "0"])))))

    (it "parses --mesh with --out FILE.stl|.ply|.obj, --resolution, --region and --gpu"
      (fn []
        (assert.are.same {:mode :mesh :scene "a.fnl" :out "a.PLY" :resolution 200 :gpu? true
                          :region {:lo [-1 -2 -3] :hi [1 2 3.5]} :frames 5 :cycles 300}
                         (cli.parse ["--mesh" "a.fnl" "--out" "a.PLY" "--resolution" "200"
                                     "--region" "-1,-2,-3,1,2,3.5" "--gpu"]))
        (assert.are.equal "--mesh needs --out FILE.stl, FILE.ply or FILE.obj"
                          (select 2 (cli.parse ["--mesh" "a.fnl"])))
        (assert.are.equal "--out must name a .stl, .ply or .obj file, got a.png"
                          (select 2 (cli.parse ["--mesh" "a.fnl" "--out" "a.png"])))
        (assert.are.equal "--resolution must be a whole number from 8 to 1024, got 7"
                          (select 2 (cli.parse ["--mesh" "a.fnl" "--out" "a.stl" "--resolution" "7"])))
        (assert.are.equal "--region: z1 must be greater than z0, got 0,0,1,1,1,1"
                          (select 2 (cli.parse ["--mesh" "a.fnl" "--out" "a.stl" "--region" "0,0,1,1,1,1"])))
        (assert.are.equal "--region only goes with --mesh"
                          (select 2 (cli.parse ["--render" "a.fnl" "--out" "a.png" "--region" "0,0,0,1,1,1"])))
        (assert.are.equal "the output file is the scene file a.stl; choose another name"
                          (select 2 (cli.parse ["--mesh" "a.stl" "--out" "./a.stl"])))))

    (it "plays a scene given as the only argument"
      (fn []
        (assert.are.same {:mode :play :scene "scenes/other.fnl" :frames 5 :cycles 300}
                         (cli.parse ["scenes/other.fnl"]))))

    (it "parses --render with --out, --size and --view"
      (fn []
        (assert.are.same {:mode :render :scene "a.fnl" :out "out/a.png" :size [640 480]
                          :view "normals" :frames 5 :cycles 300}
                         (cli.parse ["--render" "a.fnl" "--out" "out/a.png" "--size" "640x480"
                                     "--view" "normals"]))
        ;; Options may come before the mode.
        (assert.are.same {:mode :render :scene "a.fnl" :out "b.png" :frames 5 :cycles 300}
                         (cli.parse ["--out" "b.png" "--render" "a.fnl"]))))

    (it "parses --print-shader with --view and --target"
      (fn []
        (assert.are.same {:mode :print-shader :scene "a.fnl" :view "heat" :target "core" :frames 5 :cycles 300}
                         (cli.parse ["--print-shader" "a.fnl" "--view" "heat" "--target" "core"]))
        (assert.are.same {:mode :print-shader :scene "a.fnl" :target "love" :frames 5 :cycles 300}
                         (cli.parse ["--print-shader" "a.fnl" "--target" "love"]))))

    (it "parses --bench with --size and --frames"
      (fn []
        (assert.are.same {:mode :bench :scene "a.fnl" :size [1920 1080] :frames 30 :cycles 300}
                         (cli.parse ["--bench" "a.fnl" "--size" "1920X1080" "--frames" "30"]))
        (assert.are.same {:mode :bench :scene "a.fnl" :frames 5 :cycles 300} (cli.parse ["--bench" "a.fnl"]))))

    (it "parses --bench-report with the default scene and --frames"
      (fn []
        (assert.are.same {:mode :bench-report :scene "scenes/seed.fnl" :frames 5 :cycles 300}
                         (cli.parse ["--bench-report"]))
        (assert.are.same {:mode :bench-report :scene "scenes/seed.fnl" :frames 2 :cycles 300}
                         (cli.parse ["--bench-report" "--frames" "2"]))))

    (it "parses --soak with --cycles"
      (fn []
        (assert.are.same {:mode :soak :scene "scenes/seed.fnl" :frames 5 :cycles 1000}
                         (cli.parse ["--soak" "--cycles" "1000"]))
        (assert.are.equal "--cycles must be a whole number >= 1, got 0"
                          (select 2 (cli.parse ["--soak" "--cycles" "0"])))))

    (it "parses --shot with play mode"
      (fn []
        (assert.are.same {:mode :play :scene "a.fnl" :shot "s.png" :frames 3 :cycles 300}
                         (cli.parse ["a.fnl" "--shot" "s.png" "--frames" "3"]))
        (assert.are.same {:mode :play :scene "scenes/seed.fnl" :shot "s.png" :frames 5 :cycles 300}
                         (cli.parse ["--shot" "s.png"]))))

    (it "accepts every view and the size limits"
      (fn []
        (each [_ view (ipairs [:shaded :normals :glow :heat])]
          (assert.are.equal view (. (cli.parse ["--view" view]) :view)))
        (assert.are.same [1 1] (. (cli.parse ["--size" "1x1"]) :size))
        (assert.are.same [16384 16384] (. (cli.parse ["--size" "16384x16384"]) :size))))

    (it "has a usage text naming every user's mode and view, and the developers' apart"
      (fn []
        (each [_ s (ipairs ["--render" "--record" "--out" "--print-shader" "--bench" "--probe"
                            "--tree" "--kinds" "--export-shader" "--mesh" "--sync-compile"
                            "--size" "--frames" "--view" "--target" "--shot" "--quality"
                            "--samples" "draft" "still" "final" "--help-dev"
                            "shaded, normals, glow, heat"])]
          (assert.truthy (cli.usage:find s 1 true) s))
        ;; The internal modes (tests, benchmarks, the player's helpers) are not the
        ;; user's: --help-dev lists them.
        (each [_ s (ipairs ["--bench-report" "--soak" "--input-check" "--edit-latency"
                            "--warm-shader" "--warm-server" "--scene-worker"])]
          (assert.falsy (cli.usage:find s 1 true) s)
          (assert.truthy (cli.dev-usage:find s 1 true) s))))

    (it "parses --help-dev"
      (fn []
        (assert.are.equal :help-dev (. (cli.parse ["--help-dev"]) :mode))))

    (it "parses --quality and --samples for --render and --record, absent unless given"
      (fn []
        (assert.are.same {:mode :render :scene "a.fnl" :out "a.png" :quality "final" :samples 8
                          :frames 5 :cycles 300}
                         (cli.parse ["--render" "a.fnl" "--out" "a.png" "--quality" "final"
                                     "--samples" "8"]))
        (assert.are.same {:mode :record :scene "a.fnl" :out "d" :samples 1 :frames 5 :cycles 300}
                         (cli.parse ["--record" "a.fnl" "--out" "d" "--samples" "1"]))
        (assert.are.equal "draft" (. (cli.parse ["--render" "a.fnl" "--out" "a.png" "--quality" "draft"
                                                 "--samples" "1"])
                                     :quality))
        (assert.is_nil (. (cli.parse ["--render" "a.fnl" "--out" "a.png"]) :samples))))))

(describe "cli: errors"
  (fn []
    (it "rejects unknown options"
      (fn []
        (assert.are.equal "unknown option --fast" (parse-error ["--fast"]))
        (assert.are.equal "unknown option --out=a.png" (parse-error ["--render" "a.fnl" "--out=a.png"]))))

    (it "needs --out for --render, and a .png"
      (fn []
        (assert.are.equal "--render needs --out FILE.png" (parse-error ["--render" "a.fnl"]))
        (assert.are.equal "--out must name a .png file, got a.jpg"
                          (parse-error ["--render" "a.fnl" "--out" "a.jpg"]))
        (assert.are.equal "--out must name a .png file, got --size"
                          (parse-error ["--render" "a.fnl" "--out" "--size"]))))

    (it "needs a scene after a mode flag and a value after an option"
      (fn []
        (assert.are.equal "--render needs a scene file" (parse-error ["--render"]))
        (assert.are.equal "--render needs a scene file" (parse-error ["--render" "--out" "a.png"]))
        (assert.are.equal "--bench needs a scene file" (parse-error ["--bench"]))
        (assert.are.equal "--print-shader needs a scene file" (parse-error ["--print-shader"]))
        (assert.are.equal "--out needs a value" (parse-error ["--render" "a.fnl" "--out"]))
        (assert.are.equal "--frames needs a value" (parse-error ["--frames"]))))

    (it "rejects bad sizes"
      (fn []
        (each [_ s (ipairs ["640" "640x" "x480" "0x480" "640x0" "-640x480" "640*480"
                            "16385x100" "100x16385" "640x480x2" "1.5x2" "axb" ""])]
          (assert.are.equal (.. "--size must look like 1920x1080, got " s)
                            (parse-error ["--bench" "a.fnl" "--size" s])))))

    (it "rejects bad frame counts"
      (fn []
        (each [_ n (ipairs ["0" "-1" "1.5" "abc" "" "nan"])]
          (assert.are.equal (.. "--frames must be a whole number >= 1, got " n)
                            (parse-error ["--bench" "a.fnl" "--frames" n])))))

    (it "rejects an infinite frame count"
      (fn []
        (assert.are.equal "--frames must be a whole number >= 1, got 1e999"
                          (parse-error ["--bench" "a.fnl" "--frames" "1e999"]))))

    (it "rejects bad views and targets"
      (fn []
        (assert.are.equal "--view must be one of shaded, normals, glow, heat, got bogus"
                          (parse-error ["--view" "bogus"]))
        (assert.are.equal "--view must be one of shaded, normals, glow, heat, got Shaded"
                          (parse-error ["--render" "a.fnl" "--out" "a.png" "--view" "Shaded"]))
        (assert.are.equal "--target must be love or core, got gles"
                          (parse-error ["--print-shader" "a.fnl" "--target" "gles"]))))

    (it "rejects --shot outside play mode or without .png"
      (fn []
        (assert.are.equal "--shot must name a .png file, got s.jpg"
                          (parse-error ["a.fnl" "--shot" "s.jpg"]))
        (assert.are.equal "--shot only goes with playing a scene"
                          (parse-error ["--bench" "a.fnl" "--shot" "s.png"]))
        (assert.are.equal "--shot needs a value" (parse-error ["--shot"]))))

    (it "rejects two modes"
      (fn []
        (assert.are.equal "--bench: only one mode at a time"
                          (parse-error ["--render" "a.fnl" "--out" "a.png" "--bench" "b.fnl"]))
        (assert.are.equal "--render: only one mode at a time"
                          (parse-error ["--print-shader" "a.fnl" "--render" "b.fnl"]))
        (assert.are.equal "--bench-report: only one mode at a time"
                          (parse-error ["--bench" "a.fnl" "--bench-report"]))
        (assert.are.equal "--bench: only one mode at a time"
                          (parse-error ["--bench-report" "--bench" "a.fnl"]))
        (assert.are.equal "--bench-report: only one mode at a time"
                          (parse-error ["--bench-report" "--bench-report"]))))

    (it "rejects a second scene"
      (fn []
        (assert.are.equal "unexpected argument b.fnl" (parse-error ["a.fnl" "b.fnl"]))
        (assert.are.equal "unexpected argument b.fnl" (parse-error ["--bench" "a.fnl" "b.fnl"]))))

    (it "rejects bad --quality and --samples, and either outside --render and --record"
      (fn []
        (assert.are.equal "--quality must be one of draft, still, final, got best"
                          (parse-error ["--render" "a.fnl" "--out" "a.png" "--quality" "best"]))
        (each [_ n (ipairs ["0" "2.5" "x"])]
          (assert.are.equal (.. "--samples must be a whole number >= 1, got " n)
                            (parse-error ["--render" "a.fnl" "--out" "a.png" "--samples" n])))
        (assert.are.equal "--samples must be at most 16, got 17"
                          (parse-error ["--render" "a.fnl" "--out" "a.png" "--samples" "17"]))
        (assert.are.equal "--quality draft is one ray a pixel: --samples above 1 goes with still or final"
                          (parse-error ["--render" "a.fnl" "--out" "a.png" "--quality" "draft" "--samples" "4"]))
        (assert.are.equal "--samples only goes with --render or --record"
                          (parse-error ["--bench" "a.fnl" "--samples" "4"]))
        (assert.are.equal "--quality only goes with --render or --record"
                          (parse-error ["a.fnl" "--quality" "final"]))
        (assert.are.equal "--quality needs a value" (parse-error ["--render" "a.fnl" "--quality"]))))

    (it "reports the first error only"
      (fn []
        (assert.are.equal "unknown option --x" (parse-error ["--x" "--size" "bad"]))))))

(describe "cli: --time"
  (fn []
    (it "takes seconds for --render only, finite and not negative"
      (fn []
        (assert.are.equal 2.5 (. (cli.parse ["--render" "a.fnl" "--out" "a.png" "--time" "2.5"]) :time))
        (assert.are.same [nil "--time only goes with --render (--record steps through time itself)"]
                         [(cli.parse ["--record" "a.fnl" "--out" "d" "--frames" "2" "--time" "1"])])
        (each [_ bad (ipairs ["-1" "abc" "nan" "inf" "1e10"])]
          (assert.are.same [nil (.. "--time must be a number of seconds from 0 to 1e9, got " bad)]
                           [(cli.parse ["--render" "a.fnl" "--out" "a.png" "--time" bad])]))))))

;; The real app, run headless (SDL_VIDEODRIVER=offscreen) through its command line.
(local png (require :src.util.png))
(local {: sh : root : hang-seconds &as app} (require :test.support.app))

;; `love . ARGS` headless: exit code and combined output.
(local run app.love)

(fn write-file [path text]
  (with-open [f (assert (io.open path :wb))] (f:write text)))

(describe "the app's command line"
  (fn []
    (os.execute "mkdir -p test/out")

    (it "renders the seed scene to a PNG of the asked size"
      (fn []
        (os.remove "test/out/app-seed.png")
        (let [(code out) (run "--render scenes/seed.fnl --out test/out/app-seed.png --size 64x48")]
          (assert.are.equal 0 code out)
          (let [img (assert (png.read-file "test/out/app-seed.png"))]
            (assert.are.equal 64 img.width)
            (assert.are.equal 48 img.height)
            ;; The top row is sky: the environment colour [0.901 0.976 1].
            (assert.are.same [230 249 255] [(. img.pixels 0) (. img.pixels 1) (. img.pixels 2)])))))

    (it "renders each debug view"
      (fn []
        (each [_ view (ipairs [:normals :glow :heat])]
          (let [(code out) (run (.. "--render scenes/seed.fnl --view " view
                                    " --out test/out/app-" view ".png --size 32x24"))]
            (assert.are.equal 0 code out)))))

    (it "prints the generated shader"
      (fn []
        (let [(code out) (run "--print-shader scenes/spheres.fnl")]
          (assert.are.equal 0 code)
          (assert.truthy (out:find "sdSphere" 1 true))
          (assert.falsy (out:find "sdBox" 1 true)))))

    (it "benchmarks a scene and prints the median"
      (fn []
        (let [(code out) (run "--bench scenes/flat.fnl --size 32x24 --frames 2")]
          (assert.are.equal 0 code out)
          (assert.truthy (out:find "median [%d%.]+ ms per frame over 2 frames")))))

    (it "plays a few frames and saves the window with its HUD"
      (fn []
        (os.remove "test/out/app-play.png")
        (let [(code out) (run "scenes/flat.fnl --shot test/out/app-play.png --frames 2")]
          (assert.are.equal 0 code out)
          (let [img (assert (png.read-file "test/out/app-play.png"))]
            (assert.are.equal 1280 img.width)))))

    (it "rejects a bad scene with file, line and field, exit code 1"
      (fn []
        (write-file "test/out/bad.fnl" "{:objects [{:kind :sphere\n  :radius -2}]}")
        (let [(code out) (run "--render test/out/bad.fnl --out test/out/bad.png")]
          (assert.are.equal 1 code)
          (assert.truthy (out:find "test/out/bad.fnl:2: objects[1].radius: must be a positive number from 1e-6 to 1e7, got -2" 1 true)))))

    (it "rejects bad arguments with the usage, exit code 1"
      (fn []
        (each [_ args (ipairs ["--bogus" "--render scenes/seed.fnl" "--render scenes/seed.fnl --out x.png --size 12"
                               "--render scenes/missing.fnl --out test/out/m.png"])]
          (let [(code out) (run args)]
            (assert.are.equal 1 code args)
            (assert.truthy (out:find "error: " 1 true) args)))
        ;; An argument error: its message and one line pointing at --help, not the
        ;; whole usage after it.
        (let [(code out) (run "--bogus")]
          (assert.are.equal 1 code out)
          (assert.truthy (out:find "error: unknown option --bogus\n(love . --help lists the modes and options)" 1 true) out)
          (assert.falsy (out:find "usage:" 1 true) out))))

    (it "prints the generated shader from another working directory"
      (fn []
        (let [(code text) (sh (.. "cd /tmp && SDL_VIDEODRIVER=offscreen timeout " hang-seconds " love "
                                  root " --print-shader " root "/scenes/seed.fnl"))]
          (assert.are.equal 0 code text)
          (assert.truthy (text:find "float raymarch(" 1 true) text))))

    (it "lists every primitive and operation with --kinds"
      (fn []
        (let [(code out) (run "--kinds")]
          (assert.are.equal 0 code out)
          (assert.truthy (out:find "primitives %(%d+%)"))
          (assert.truthy (out:find "  :torus  exact  :radius 1, :thickness 0.25" 1 true) out)
          (assert.truthy (out:find "  :ellipsoid  bound  " 1 true) out)
          (assert.truthy (out:find "  :smooth-union  2+ children  bound  :radius 0.25, :kernel :poly" 1 true) out))))

    (it "prints the lowered tree with each node's class with --tree"
      (fn []
        (let [(code out) (run "--tree scenes/twisted-tower.fnl")]
          (assert.are.equal 0 code out)
          (assert.truthy (out:find "translate (shorthand)  exact  unbounded  objects[1]\n  plane  exact  unbounded  objects[1]" 1 true) out)
          (assert.truthy (out:find "twist  bound, Lipschitz" 1 true) out)
          (assert.truthy (out:find "objects[2].children[2]" 1 true) out))))

    (it "refuses --gpu without --probe"
      (fn []
        (let [(code out) (run "--render scenes/seed.fnl --out test/out/x.png --gpu")]
          (assert.are.equal 1 code)
          (assert.truthy (out:find "--gpu only goes with --probe" 1 true) out))))

    (it "fills the window at a render scale that does not divide it (no black strips)"
      (fn []
        (write-file "test/out/scale77.fnl"
                    "{:render {:scale 0.77 :reflections 0 :shadows false}
 :environment [0.5 0.6 0.7]
 :objects [{:kind :plane :height 0 :color [0.8 0.8 0.8]}]}")
        (os.remove "test/out/scale77.png")
        (let [(code out) (run "test/out/scale77.fnl --shot test/out/scale77.png --frames 2")
              img (assert (png.read-file "test/out/scale77.png") out)
              px (fn [x y] (let [i (* 4 (+ x (* y img.width)))]
                             (+ (. img.pixels i) (. img.pixels (+ i 1)) (. img.pixels (+ i 2)))))]
          (assert.are.equal 0 code out)
          ;; The last column and the last row show the scene, not the black clear colour.
          (assert.is_true (> (px (- img.width 1) 10) 0) "black strip at the right")
          (assert.is_true (> (px 10 (- img.height 1)) 0) "black strip at the bottom"))))

    (it "make run says there is no display and exits non-zero without one"
      (fn []
        (let [(code text) (sh (.. "env -u DISPLAY -u WAYLAND_DISPLAY -u SDL_VIDEODRIVER timeout " hang-seconds " make -s run"))]
          (assert.truthy (text:find "make run: no display" 1 true) text)
          (assert.are_not.equal 0 code text))))

    (it "packs a .love that plays bundled and outside scenes from another directory"
      (fn []
        (let [(code out) (sh "bash tools/dist.sh")]
          (assert.are.equal 0 code out)
          (each [_ scene (ipairs ["scenes/organic.fnl" (.. root "/scenes/flower.fnl")])]
            (os.remove "/tmp/raymarcher-dist-test.png")
            (let [(rcode rout) (sh (.. "cd /tmp && SDL_VIDEODRIVER=offscreen timeout " hang-seconds " love " root
                                       "/dist/fennel-raymarcher.love --render " scene
                                       " --out /tmp/raymarcher-dist-test.png --size 64x48"))]
              (assert.are.equal 0 rcode rout)
              (assert.truthy (png.read-file "/tmp/raymarcher-dist-test.png") rout)))
          (os.remove "/tmp/raymarcher-dist-test.png"))))

    (it "records the same frames twice, and a turntable turns"
      (fn []
        (os.execute "rm -rf test/out/rec-a test/out/rec-b")
        (let [(code out) (run "--record scenes/flower.fnl --out test/out/rec-a --frames 3 --size 32x24 --turntable")
              (code2 out2) (run "--record scenes/flower.fnl --out test/out/rec-b --frames 3 --size 32x24 --turntable")
              read (fn [path] (with-open [f (assert (io.open path :rb))] (f:read :*a)))]
          (assert.are.equal 0 code out)
          (assert.are.equal 0 code2 out2)
          (assert.truthy (out:find "frame 3/3" 1 true) out)
          ;; stderr is a pipe here, not a terminal: one line an update, no \r.
          (assert.truthy (out:find "frame 1/3 (t = 0.000 s)\nframe 2/3" 1 true) out)
          (assert.falsy (out:find "\r" 1 true) out)
          (for [i 1 3]
            (let [name (string.format "frame-%04d.png" i)]
              (assert.are.equal (read (.. "test/out/rec-a/" name)) (read (.. "test/out/rec-b/" name)) name)))
          (assert.are_not.equal (read "test/out/rec-a/frame-0001.png") (read "test/out/rec-a/frame-0002.png")))))))

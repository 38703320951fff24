;; Command-line arguments of the app: which mode to run and with what, checked before
;; anything opens. Pure: a list of strings in, an options table or an error out.

(local plan (require :src.render.plan))
(local mesh-options (require :src.mesh.options))

(local default-scene "scenes/seed.fnl")

;; --quality's names (see src/app/quality.fnl).
(local qualities {:draft true :still true :final true})

(local usage
  "usage: love . [SCENE] [--target-fps N]      play SCENE (default scenes/seed.fnl), moving at N fps (30)
       love . [SCENE] --sync-compile         play, compiling a changed scene's shader in the player
                                             (default: a helper process compiles it first)
       love . [SCENE] --shot FILE.png [--frames N]   play N frames, save the window, quit
       love . --render SCENE --out FILE.png [--size WxH] [--view VIEW] [--quality Q] [--samples N]
                      [--time T]             the picture as the player's anti-aliased still, its
                                             functions of time at T seconds (0)
       love . --record SCENE --out DIR --frames N [--fps F] [--size WxH] [--turntable]
                      [--quality Q] [--samples N]   frames DIR/frame-0001.png ..., each a still
       love . --export-shader SCENE --out FILE.glsl   a Shadertoy shader with the values baked in
       love . --mesh SCENE --out FILE.stl|.ply|.obj [--resolution N] [--region x0,y0,z0,x1,y1,z1] [--gpu]
                      [--adaptive E]         a mesh of the scene's finite objects (N cells along
                                             the longest side, 128), or of all of them cut by a box;
                                             --adaptive: triangles merged while within E of the surface
       love . --print-shader SCENE [--view VIEW] [--target love|core] [--interpret]
       love . --bench SCENE [--size WxH] [--frames N] [--interpret]   median ms per frame
       love . --probe SCENE [--gpu]          distance and material at points `x y z` read from stdin
       love . --tree SCENE                   the lowered scene tree, each node's class and bounds
       love . --kinds                        every primitive and operation, with parameters
       love . --help                         this text (--help-dev: the developers' modes)
VIEW is one of shaded, normals, glow, heat.
Q (--render, --record) is one of
  draft   one ray a pixel (what the player shows while the scene moves; the goldens')
  still   the player's anti-aliased still, the default: one ray, and N x N rays (4) only
          where the pixel holds an edge or a second ray disagrees
  final   N x N rays (4) in every pixel: slowest, catches what the edge tests miss
--samples N (1 to 16): N x N rays at most a pixel; --samples 1 is draft, the one-ray picture.
Only the shaded view has the still's edge tests: other views are drafts unless Q or N says.
--interpret (--render, --bench, --print-shader): the tape interpreter's shader, which draws
any scene of its instruction set (every kind, and the scene's own forms) without a compile.")

(local dev-usage
  "developers' modes (tests, benchmarks and the player's own helpers):
       love . --bench-report [--frames N]    the benchmark behind `make bench`
       love . --soak [SCENE] [--cycles N]    hot-reload soak test (edits a temp scene)
       love . --input-check                  the player driven by scripted keys and mouse
       love . --edit-latency SCENE [--sync-compile]   the player's delay in showing an edit
       love . --edit-latency SCENE --preview-check   a structural edit whose shader never comes:
                                             its CPU preview must show the new scene, alone
       love . --edit-latency SCENE --interpret-check   a structural edit drawn by the tape interpreter
                                             (its shader built first, the helper then held): the new
                                             scene at once, the reference's picture, then its own shader
       love . [SCENE] --interpret-edits      draw structural edits with the tape interpreter while the
                                             helper compiles (the default on a GPU, not on llvmpipe;
                                             also with --edit-latency)
       love . --warm-shader FILE.glsl        compile a shader and draw it once (the player's helper;
                                             conf.lua runs it before anything else)
       love . --warm-server DIR PID          the player's compile helper, serving DIR until PID ends
       love . --scene-worker                 the process that runs scene files (conf.lua starts it
                                             with the file system only)
       love . --help-dev                     this text")

(local value-flags {:--out :out :--size :size :--frames :frames :--view :view :--time :time
                    :--target :target :--shot :shot :--cycles :cycles :--fps :fps
                    :--target-fps :target-fps :--resolution :resolution :--region :region :--adaptive :adaptive
                    :--samples :samples :--quality :quality})
(local mode-flags {:--render :render :--print-shader :print-shader :--bench :bench
                   :--probe :probe :--tree :tree :--export-shader :export-shader
                   :--record :record :--edit-latency :edit-latency :--mesh :mesh})

(fn parse-size [s]
  (let [(w h) (s:match "^(%d+)[xX](%d+)$")
        w (tonumber w) h (tonumber h)]
    (when (and w h (>= w 1) (>= h 1) (<= w 16384) (<= h 16384))
      [w h])))

(fn normalize-path [p]
  "`p` without ./ segments and repeated slashes, for comparing two command-line paths."
  (var out (p:gsub "/+" "/"))
  (var again? true)
  (while again?
    (let [(next-out n) (out:gsub "/%./" "/")]
      (set out next-out)
      (set again? (> n 0))))
  (pick-values 1 (-> out (: :gsub "^%./" "") (: :gsub "/%.$" ""))))

(fn same-path? [a b]
  (and a b (= (normalize-path a) (normalize-path b))))

(fn check-options [o]
  (if (and (= o.mode :render) (not o.out))
      (values nil "--render needs --out FILE.png")
      (and (= o.mode :record) (not o.out))
      (values nil "--record needs --out DIR")
      (and o.turntable? (not= o.mode :record))
      (values nil "--turntable only goes with --record")
      (and o.fps (not= o.mode :record))
      (values nil "--fps only goes with --record")
      (and o.target-fps (not= o.mode :play))
      (values nil "--target-fps only goes with playing a scene")
      (and o.target-fps (> o.target-fps 240))
      (values nil (.. "--target-fps must be at most 240, got " o.target-fps))
      (and (= o.mode :export-shader) (not o.out))
      (values nil "--export-shader needs --out FILE.glsl")
      (and o.out (= o.mode :export-shader) (not (o.out:match "%.glsl$")))
      (values nil (.. "--out must name a .glsl file, got " o.out))
      (and (= o.mode :mesh) (not o.out))
      (values nil "--mesh needs --out FILE.stl, FILE.ply or FILE.obj")
      (and (= o.mode :mesh) (not (let [e (: (or (o.out:match "%.(%w+)$") "") :lower)]
                                   (or (= e "stl") (= e "ply") (= e "obj")))))
      (values nil (.. "--out must name a .stl, .ply or .obj file, got " o.out))
      (and (or o.resolution o.region o.adaptive) (not= o.mode :mesh))
      (values nil (.. (if o.resolution "--resolution" o.region "--region" "--adaptive")
                      " only goes with --mesh"))
      (and o.out (not= o.mode :export-shader) (not= o.mode :record) (not= o.mode :mesh)
           (not (o.out:match "%.png$")))
      (values nil (.. "--out must name a .png file, got " o.out))
      (and o.shot (not (o.shot:match "%.png$")))
      (values nil (.. "--shot must name a .png file, got " o.shot))
      (or (same-path? o.out o.scene) (same-path? o.shot o.scene))
      (values nil (.. "the output file is the scene file " o.scene "; choose another name"))
      (and o.sync-compile? (not= o.mode :play) (not= o.mode :edit-latency))
      (values nil "--sync-compile only goes with playing a scene or --edit-latency")
      (and o.preview-check? (or (not= o.mode :edit-latency) o.sync-compile?))
      (values nil "--preview-check only goes with --edit-latency (and the compile helper)")
      (and o.shot (not= o.mode :play))
      (values nil "--shot only goes with playing a scene")
      (and o.interpret? (not= o.mode :bench) (not= o.mode :print-shader) (not= o.mode :render))
      (values nil "--interpret only goes with --render, --bench or --print-shader")
      (and o.interpret-check? (or o.sync-compile? o.preview-check? (not= o.mode :edit-latency)))
      (values nil "--interpret-check only goes with --edit-latency (and the compile helper)")
      (and o.interpret-edits? (or o.sync-compile? (and (not= o.mode :play) (not= o.mode :edit-latency))))
      (values nil "--interpret-edits only goes with playing a scene or --edit-latency (and the compile helper)")
      (and o.gpu? (not= o.mode :probe) (not= o.mode :mesh))
      (values nil "--gpu only goes with --probe or --mesh")
      (and o.view (not (plan.view? o.view)))
      (values nil (.. "--view must be one of " (table.concat plan.views ", ") ", got " o.view))
      (and o.target (not= o.target "love") (not= o.target "core"))
      (values nil (.. "--target must be love or core, got " o.target))
      (and (or o.samples o.quality) (not= o.mode :render) (not= o.mode :record))
      (values nil (.. (if o.samples "--samples" "--quality") " only goes with --render or --record"))
      (and o.time (not= o.mode :render))
      (values nil "--time only goes with --render (--record steps through time itself)")
      (and o.quality (not (. qualities o.quality)))
      (values nil (.. "--quality must be one of draft, still, final, got " o.quality))
      (and o.samples (> o.samples 16))
      (values nil (.. "--samples must be at most 16, got " o.samples))
      (and (= o.quality "draft") o.samples (> o.samples 1))
      (values nil "--quality draft is one ray a pixel: --samples above 1 goes with still or final")
      o))

(fn parse [args]
  "Parse the game's arguments (after LÖVE's own). Returns an options table
{:mode :play|:render|:print-shader|:bench|:bench-report|:soak|:input-check|:probe|:tree|:kinds|:help
 |:help-dev|:export-shader|:record|:edit-latency|:mesh
 :scene :out :size [w h] :frames n :view v :target t :gpu? (probe or mesh on the GPU)
 :interpret? (render, bench, print-shader: the tape interpreter's shader)
 :resolution n :region {:lo :hi} :adaptive e (--mesh) :quality \"draft\"|\"still\"|\"final\" :samples n
 (--render, --record; absent when not given) :time t (--render)} or nil and a message (the usage text follows it)."
  (let [o {:mode :play :frames 5 :cycles 300}]
    (var i 1)
    (var err nil)
    (while (and (not err) (<= i (length args)))
      (let [a (. args i)
            next-arg (. args (+ i 1))]
        (if (. mode-flags a)
            (if (not= o.mode :play) (set err (.. a ": only one mode at a time"))
                (or (= next-arg nil) (next-arg:match "^%-%-"))
                (set err (.. a " needs a scene file"))
                (do (set o.mode (. mode-flags a))
                    (set o.scene next-arg)
                    (set i (+ i 1))))
            (= a "--gpu") (set o.gpu? true)
            (= a "--turntable") (set o.turntable? true)
            (= a "--sync-compile") (set o.sync-compile? true)
            (= a "--preview-check") (set o.preview-check? true)
            (= a "--interpret") (set o.interpret? true)
            (= a "--interpret-edits") (set o.interpret-edits? true)
            (= a "--interpret-check") (set o.interpret-check? true)
            (or (= a "--help") (= a "-h"))
            (set o.mode :help)
            (= a "--help-dev")
            (set o.mode :help-dev)
            (or (= a "--bench-report") (= a "--soak") (= a "--kinds") (= a "--input-check"))
            (if (not= o.mode :play) (set err (.. a ": only one mode at a time"))
                (set o.mode (a:sub 3)))
            (. value-flags a)
            (if (= next-arg nil) (set err (.. a " needs a value"))
                (do (tset o (. value-flags a) next-arg)
                    (set i (+ i 1))))
            ;; -x as well as --x: a single-dash word is never a scene file.
            (a:match "^%-.") (set err (.. "unknown option " a))
            o.scene (set err (.. "unexpected argument " a))
            (set o.scene a)))
      (set i (+ i 1)))
    (when (and (not err) o.size)
      (let [size (parse-size o.size)]
        (if size (set o.size size)
            (set err (.. "--size must look like 1920x1080, got " o.size)))))
    (each [_ field (ipairs [:frames :cycles :fps :target-fps :samples])]
      (when (and (not err) (= (type (. o field)) :string))
        (let [n (tonumber (. o field))]
          (if (and n (>= n 1) (< n math.huge) (= n (math.floor n))) (tset o field n)
              (set err (.. "--" field " must be a whole number >= 1, got " (. o field)))))))
    (when (and (not err) o.time)
      ;; Seconds, as the player's clock counts them: finite, not negative, and within
      ;; what a double holds to the millisecond.
      (let [t (tonumber o.time)]
        (if (and t (= t t) (>= t 0) (<= t 1e9)) (set o.time t)
            (set err (.. "--time must be a number of seconds from 0 to 1e9, got " o.time)))))
    (when (and (not err) o.resolution)
      (case (mesh-options.parse-resolution o.resolution)
        n (set o.resolution n)
        (nil e) (set err e)))
    (when (and (not err) o.adaptive)
      (case (mesh-options.parse-adaptive o.adaptive)
        e (set o.adaptive e)
        (nil e) (set err e)))
    (when (and (not err) o.region)
      (case (mesh-options.parse-region o.region)
        r (set o.region r)
        (nil e) (set err e)))
    (when (not o.scene) (set o.scene default-scene))
    (if err (values nil err) (check-options o))))

{: parse : usage : dev-usage : default-scene : same-path?}

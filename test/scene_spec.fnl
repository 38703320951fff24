;; tier: fast
;; Specs for src/scene/load.fnl: the seed scene's values, defaults, and the exact
;; "file:line: field: reason" messages for bad input.
(local scene (require :src.scene.load))

(fn load-error [source ?file]
  "The error message for scene `source`; fails when the scene loads."
  (let [(s err) (scene.load-string source (or ?file "t.fnl"))]
    (assert.is_nil s)
    (assert.are.equal :string (type err))
    err))

(describe "scene loader: the seed scene"
  (fn []
    (local s (assert (scene.load-file "scenes/seed.fnl")))

    (it "has the name, file and camera of the article's scene"
      (fn []
        (assert.are.equal "seed" s.name)
        (assert.are.equal "scenes/seed.fnl" s.file)
        (assert.are.same [20 50 20] s.camera.pos)
        (assert.are.equal 255 s.camera.yaw)
        (assert.are.equal 15 s.camera.pitch)
        (assert.are.equal 60 s.camera.fov)))

    (it "has the light, environment and render settings"
      (fn []
        (assert.are.same [-30 20 20] s.light.pos)
        (assert.are.same [0.901 0.976 1] s.environment)
        (assert.are.same {:max-steps 500 :epsilon 1e-4 :draw-distance 1000
                          :reflections 3 :shadows true :glow false :scale 1
                          :hit-test :fixed :normals :one-sided :normals-of :scene :relaxation 1 :bounds false
                          :out-of-steps :surface :samples 1 :adaptive false}
                         s.render)))

    (it "has three boxes, two spheres and a plane, in file order"
      (fn []
        (assert.are.equal 6 (length s.objects))
        (assert.are.same [:box :box :box :sphere :sphere :plane]
                         (icollect [_ o (ipairs s.objects)] o.kind))
        (assert.are.same (fcollect [i 1 6] i)
                         (icollect [_ o (ipairs s.objects)] o.index))))

    (it "has the boxes' sizes, positions and colours"
      (fn []
        (let [[b1 b2 b3] s.objects]
          (assert.are.same {:kind :box :index 1 :size [5 5 5] :pos [-2.7 -2 2.5]
                            :color [0.79 0.69 0.59]} b1)
          (assert.are.same {:kind :box :index 2 :size [5 5 5] :pos [2.7 2 2.5]
                            :color [0.75 0.08 0.66]} b2)
          (assert.are.same {:kind :box :index 3 :size [5 5 5] :pos [0 0 7.5]
                            :color [0.33 0.73 0.42]} b3))))

    (it "has the spheres' radii, positions and colours and the plane"
      (fn []
        (let [s1 (. s.objects 4) s2 (. s.objects 5) p (. s.objects 6)]
          (assert.are.same {:kind :sphere :index 4 :radius 2.5 :pos [-2.7 2.5 2.5]
                            :color [0.56 0.11 0.05]} s1)
          (assert.are.same {:kind :sphere :index 5 :radius 10 :pos [6 -20 10]
                            :color [0.97 0.71 0.17]} s2)
          (assert.are.same {:kind :plane :index 6 :height 0 :color [0.97 0.27 0.35]} p))))

    (it "loads the same through a custom reader"
      (fn []
        (let [f (assert (io.open "scenes/seed.fnl" :rb))
              text (f:read :*a)
              _ (f:close)
              asked []
              s2 (assert (scene.load-file "virtual/seed.fnl"
                                          (fn [p] (table.insert asked p) text)))]
          (assert.are.same ["virtual/seed.fnl"] asked)
          (assert.are.equal "seed" s2.name)
          (assert.are.equal "virtual/seed.fnl" s2.file)
          (assert.are.same s.objects s2.objects))))))

(describe "scene loader: defaults"
  (fn []
    (it "fills every section of a minimal scene"
      (fn []
        (let [s (assert (scene.load-string "{:objects []}" "dir/minimal.fnl"))]
          (assert.are.equal "minimal" s.name)
          (assert.are.equal "dir/minimal.fnl" s.file)
          (assert.are.same {:pos [0 -10 2] :yaw 90 :pitch 0 :fov 60} s.camera)
          (assert.are.same {:pos [-30 20 20]} s.light)
          (assert.are.same [0.901 0.976 1] s.environment)
          ;; The defaults chosen from the accuracy report, not the article's.
          (assert.are.same {:max-steps 500 :epsilon 1e-4 :draw-distance 1000
                            :reflections 3 :shadows true :glow false :scale 1
                            :hit-test :relative :normals :tetrahedron :normals-of :object :relaxation 1.5
                            :bounds true :out-of-steps :background :samples 1 :adaptive false}
                           s.render)
          (assert.are.same [] s.objects))))

    (it "names a scene without a file 'scene'"
      (fn []
        (assert.are.equal "scene" (. (assert (scene.load-string "{:objects []}")) :name))))

    (it "keeps a given name and partial sections"
      (fn []
        (let [s (assert (scene.load-string
                         "{:name \"hello\" :camera {:yaw 10} :render {:shadows false}
                           :objects []}" "t.fnl"))]
          (assert.are.equal "hello" s.name)
          (assert.are.same {:pos [0 -10 2] :yaw 10 :pitch 0 :fov 60} s.camera)
          (assert.are.equal false s.render.shadows)
          (assert.are.equal 500 s.render.max-steps))))

    (it "fills the article's flat objects' parameters from the primitives' defaults"
      (fn []
        (let [s (assert (scene.load-string
                         "{:objects [{:kind :sphere} {:kind :box} {:kind :plane}]}" "t.fnl"))]
          (assert.are.same [{:kind :sphere :index 1 :pos [0 0 0] :radius 1 :color [1 1 1]}
                            {:kind :box :index 2 :pos [0 0 0] :size [1 1 1] :color [1 1 1]}
                            {:kind :plane :index 3 :height 0 :color [1 1 1]}]
                           s.objects))))

    (it "accepts boundary values"
      (fn []
        (let [s (assert (scene.load-string
                         "{:camera {:pitch -90 :fov 179}
                           :render {:max-steps 1 :epsilon 0 :reflections 0 :scale 1}
                           :environment [0 0 0]
                           :objects [{:kind :sphere :color [0 1 0]}]}" "t.fnl"))]
          (assert.are.equal -90 s.camera.pitch)
          (assert.are.equal 179 s.camera.fov)
          (assert.are.equal 1 s.render.max-steps)
          (assert.are.equal 0 s.render.epsilon)
          (assert.are.equal 0 s.render.reflections)
          (assert.are.same [0 0 0] s.environment))))

    (it "evaluates computed scenes (let, math, fcollect)"
      (fn []
        (let [s (assert (scene.load-string
                         "(let [r (math.sqrt 4)]
                            {:objects (fcollect [i 1 3] {:kind :sphere :radius r :pos [i 0 0]})})"
                         "t.fnl"))]
          (assert.are.equal 3 (length s.objects))
          (assert.are.equal 2 (. s.objects 3 :radius))
          (assert.are.same [3 0 0] (. s.objects 3 :pos)))))

    (it "exposes the defaults by section"
      (fn []
        (let [d (scene.defaults)]
          (assert.are.same {:pos [0 -10 2] :yaw 90 :pitch 0 :fov 60} d.camera)
          (assert.are.same {:pos [-30 20 20]} d.light)
          (assert.are.equal 500 d.render.max-steps)
          (assert.are.same {:max-reflections 16 :max-steps 100000 :max-objects 1000000
                            :world 1e7 :min-length 1e-6 :max-epsilon 10 :min-fov 0.1
                            :max-fov 179 :max-name 80 :max-depth 32 :max-nodes 1000000}
                           scene.limits))))))

(describe "scene loader: error messages"
  (fn []
    ;; [source expected-message], every source a one-liner called t.fnl.
    (local cases
      [;; objects
       ["{:objects [{:kind :sphere :radius -1}]}"
        "t.fnl:1: objects[1].radius: must be a positive number from 1e-6 to 1e7, got -1"]
       ["{:objects [{:kind :sphere :radius 0}]}"
        "t.fnl:1: objects[1].radius: must be a positive number from 1e-6 to 1e7, got 0"]
       ["{:objects [{:kind :sphere :radius (/ 0 0)}]}"
        "t.fnl:1: objects[1].radius: must be a positive number from 1e-6 to 1e7, got nan"]
       ["{:objects [{:kind :sphere :radius (/ 1 0)}]}"
        "t.fnl:1: objects[1].radius: must be a positive number from 1e-6 to 1e7, got inf"]
       ["{:objects [{:kind :plane :height (/ -1 0)}]}"
        "t.fnl:1: objects[1].height: must be a number from -1e7 to 1e7, got -inf"]
       ["{:objects [{:kind :sphere :radius \"a\"}]}"
        "t.fnl:1: objects[1].radius: must be a positive number from 1e-6 to 1e7, got \"a\""]
       ["{:objects [{:kind :sphere :radius true}]}"
        "t.fnl:1: objects[1].radius: must be a positive number from 1e-6 to 1e7, got true"]
       ["{:objects [{:kind :sphere :pos [1 2]}]}"
        "t.fnl:1: objects[1].pos: must be a list of three numbers like [1 2 3], got a list of 2 items"]
       ["{:objects [{:kind :sphere :pos [1 2 (/ 0 0)]}]}"
        "t.fnl:1: objects[1].pos[3]: must be a number from -1e7 to 1e7, got nan"]
       ["{:objects [{:kind :sphere :color [1 2 0]}]}"
        "t.fnl:1: objects[1].color[2]: must be a colour of three numbers from 0 to 1, got 2"]
       ["{:objects [{:kind :sphere :color [1 -0.1 0]}]}"
        "t.fnl:1: objects[1].color[2]: must be a colour of three numbers from 0 to 1, got -0.1"]
       ["{:objects [{:kind :box :size [1 0 1]}]}"
        "t.fnl:1: objects[1].size[2]: must be a positive number from 1e-6 to 1e7, got 0"]
       ["{:objects [{:kind :box :size 5}]}"
        "t.fnl:1: objects[1].size: must be three positive numbers like [1 1 1], got 5"]
       ["{:objects [{:kind :sphere :radus 1}]}"
        "t.fnl:1: objects[1].radus: unknown field (did you mean :radius?); known fields: :color :emission :kind :mirror :pos :radius :rotate :roughness :scale"]
       ["{:objects [{:kind :plane :size [0 0 0]}]}"
        "t.fnl:1: objects[1].size: unknown field; known fields: :color :emission :height :kind :mirror :normal :pos :rotate :roughness :scale"]
       ["{:objects [{:kind :spere}]}"
        "t.fnl:1: objects[1].kind: unknown kind :spere (did you mean :sphere?) (`love . --kinds` lists them all)"]
       ["{:objects [{:kind :teapot}]}"
        "t.fnl:1: objects[1].kind: unknown kind :teapot (`love . --kinds` lists them all)"]
       ["{:objects [{:radius 1}]}"
        "t.fnl:1: objects[1]: missing :kind (see `love . --kinds` for the list)"]
       ["{:objects [{:kind 3}]}"
        "t.fnl:1: objects[1].kind: must be a kind name like :sphere, got 3"]
       ["{:objects [5]}"
        "t.fnl:1: objects[1]: must be a table like {:kind :sphere ...}, got 5"]
       ;; top level
       ["{:camera {}}"
        "t.fnl:1: objects: missing; a scene needs :objects [...] (it may be empty)"]
       ["{:objects 5}"
        "t.fnl:1: objects: must be a list of objects, got 5"]
       ["{:objects {:a 1}}"
        "t.fnl:1: objects: must be a list [...] of objects, not a table with named fields"]
       ["{:objects [] :lite {}}"
        "t.fnl:1: lite: unknown field; known fields: :camera :environment :light :lighting :name :objects :render"]
       ["{:objects [] :rendr {}}"
        "t.fnl:1: rendr: unknown field (did you mean :render?); known fields: :camera :environment :light :lighting :name :objects :render"]
       ["{:objects [] :name 5}"
        "t.fnl:1: name: must be a string, got 5"]
       ["{:objects [] :environment [2 0 0]}"
        "t.fnl:1: environment[1]: must be a colour of three numbers from 0 to 1, got 2"]
       ["{:objects [] :environment \"red\"}"
        "t.fnl:1: environment: must be a colour of three numbers from 0 to 1, got \"red\""]
       ["[1 2 3]"
        "t.fnl:1: a scene file must evaluate to a table like {:objects [...]}, got a list of 3 items"]
       ["42"
        "t.fnl: a scene file must evaluate to a table like {:objects [...]}, got 42"]
       ["\"scene\""
        "t.fnl: a scene file must evaluate to a table like {:objects [...]}, got \"scene\""]
       ;; camera
       ["{:objects [] :camera {:pitch 91}}"
        "t.fnl:1: camera.pitch: must be a number of degrees from -90 to 90, got 91"]
       ["{:objects [] :camera {:pitch -90.5}}"
        "t.fnl:1: camera.pitch: must be a number of degrees from -90 to 90, got -90.5"]
       ["{:objects [] :camera {:fov 0}}"
        "t.fnl:1: camera.fov: must be a number of degrees from 0.1 to 179, got 0"]
       ["{:objects [] :camera {:fov 180}}"
        "t.fnl:1: camera.fov: must be a number of degrees from 0.1 to 179, got 180"]
       ["{:objects [] :camera {:yaw (/ 1 0)}}"
        "t.fnl:1: camera.yaw: must be a number from -1e7 to 1e7, got inf"]
       ["{:objects [] :camera {:pos [1 2 3 4]}}"
        "t.fnl:1: camera.pos: must be a list of three numbers like [1 2 3], got a list of 4 items"]
       ["{:objects [] :camera {:pos {:x 1 :y 2 :z 3}}}"
        "t.fnl:1: camera.pos: must be a list of three numbers like [1 2 3], got a table"]
       ["{:objects [] :camera {:pos [1 2 \"3\"]}}"
        "t.fnl:1: camera.pos[3]: must be a number from -1e7 to 1e7, got \"3\""]
       ["{:objects [] :camera {:fvo 60}}"
        "t.fnl:1: camera.fvo: unknown field (did you mean :fov?); known fields: :fov :pitch :pos :yaw"]
       ["{:objects [] :camera {:yaww 60}}"
        "t.fnl:1: camera.yaww: unknown field (did you mean :yaw?); known fields: :fov :pitch :pos :yaw"]
       ["{:objects [] :camera 5}"
        "t.fnl:1: camera: must be a table like {:fov ...}, got 5"]
       ;; render
       ["{:objects [] :render {:max-steps 1.5}}"
        "t.fnl:1: render.max-steps: must be an integer from 1 to 100000, got 1.5"]
       ["{:objects [] :render {:max-steps 0}}"
        "t.fnl:1: render.max-steps: must be an integer from 1 to 100000, got 0"]
       ["{:objects [] :render {:max-steps 100001}}"
        "t.fnl:1: render.max-steps: must be an integer from 1 to 100000, got 100001"]
       ["{:objects [] :render {:reflections 17}}"
        "t.fnl:1: render.reflections: must be an integer from 0 to 16, got 17"]
       ["{:objects [] :render {:reflections -1}}"
        "t.fnl:1: render.reflections: must be an integer from 0 to 16, got -1"]
       ["{:objects [] :render {:shadows 1}}"
        "t.fnl:1: render.shadows: must be true or false, got 1"]
       ["{:objects [] :render {:glow \"yes\"}}"
        "t.fnl:1: render.glow: must be true or false, got \"yes\""]
       ["{:objects [] :render {:epsilon -1}}"
        "t.fnl:1: render.epsilon: must be a number from 0 to 10, got -1"]
       ["{:objects [] :render {:draw-distance 0}}"
        "t.fnl:1: render.draw-distance: must be a positive number from 1e-6 to 1e7, got 0"]
       ["{:objects [] :render {:scale 2}}"
        "t.fnl:1: render.scale: must be a render scale above 0 and at most 1, got 2"]])

    (it "gives the exact message for each kind of bad input"
      (fn []
        (each [_ [source expected] (ipairs cases)]
          (assert.are.equal expected (load-error source)))))

    (it "rejects more than the object limit, saying how many objects to remove"
      (fn []
        ;; One object table listed many times: cheap to build, counted all the same
        ;; (before any object is checked).
        (assert.are.equal
          "t.fnl:1: objects: has 1000001 objects; at most 1000000 are allowed (remove 1)"
          (load-error "(let [o {:kind :sphere}] {:objects (fcollect [i 1 1000001] o)})"))
        (assert.are.equal
          "t.fnl:1: objects: has 1250000 objects; at most 1000000 are allowed (remove 250000)"
          (load-error "(let [o {:kind :box}] {:objects (fcollect [i 1 1250000] o)})"))
        (assert.are.equal 1000000 (length (. (assert (scene.load-string
                                                     "(let [o {:kind :plane}] {:objects (fcollect [i 1 1000000] o)})"
                                                     "t.fnl"))
                                             :objects)))))

    (it "names the first of several bad keys in a stable order, not pairs order"
      (fn []
        (assert.are.equal
          "t.fnl:1: alpha: unknown field; known fields: :camera :environment :light :lighting :name :objects :render"
          (load-error "{:objects [] :zeta 1 :alpha 2 :mid 3}"))
        (assert.are.equal
          "t.fnl:1: unexpected entry 2; fields are named, like :name"
          (load-error "{:objects [] :zeta 1 3 :x 2 :y}"))
        (assert.are.equal
          "t.fnl:1: objects[1].aa: unknown field; known fields: :color :emission :kind :mirror :pos :radius :rotate :roughness :scale"
          (load-error "{:objects [{:kind :sphere :zz 1 :aa 2 :mm 3}]}"))))

    (it "leaves the shader's size to the plan: 501 rotated spheres load (one loop draws them)"
      (fn []
        ;; (src/render/plan.fnl refuses a shader of more than 500 distinct tree
        ;; nodes written out: test/grid_spec.fnl and the corpus.)
        (let [s (assert (scene.load-string "{:objects (fcollect [i 1 501] {:kind :sphere :rotate [0 0 i]})}" "t.fnl"))]
          (assert.are.equal 501 (length s.objects)))))

    (it "reports syntax errors with file, line and column"
      (fn []
        (assert.are.equal "t.fnl:1:11: Parse error: mismatched closing delimiter }, expected ]"
                          (load-error "{:objects [}"))
        (let [err (load-error "{:objects []\n :name \"x\"\n :camera {:pos [1 2 3]}" "t.fnl")]
          (assert.truthy (err:find "^t%.fnl:%d+:%d*:? ?Parse error"))
          ;; One line only: the source echo and caret are dropped.
          (assert.is_nil (err:find "\n")))))

    (it "gives a clean error for forbidden globals"
      (fn []
        (let [hint " (scene files are data: only math, numbers, strings and tables are available)"]
          (assert.are.equal (.. "t.fnl:1:1: Compile error: unknown identifier: os" hint)
                            (load-error "(os.execute \"true\")"))
          (assert.are.equal (.. "t.fnl:1:1: Compile error: unknown identifier: io" hint)
                            (load-error "(io.open \"x\")"))
          (assert.are.equal (.. "t.fnl:1:1: Compile error: unknown identifier: require" hint)
                            (load-error "(require :src.scene.load)"))
          (assert.are.equal (.. "t.fnl:1:1: Compile error: unknown identifier: load" hint)
                            (load-error "(load \"return 1\")"))
          (assert.are.equal (.. "t.fnl:1:1: Compile error: unknown identifier: setmetatable" hint)
                            (load-error "(setmetatable {} {})"))
          (let [err (load-error "{:objects []\n :name (os.getenv \"HOME\")}")]
            (assert.truthy (err:find "^t%.fnl:2:%d+: Compile error: unknown identifier: os")))
          (assert.truthy (: (load-error "{:objects [] :name (tostring _G)}")
                            :find "unknown identifier: _G" 1 true)))))

    (it "refuses compile-time code: macros, eval-compiler and raw Lua"
      (fn []
        (let [why ") is not allowed: scene files are data and run no compile-time code"]
          (assert.are.equal (.. "t.fnl:1: (eval-compiler ..." why)
                            (load-error "(eval-compiler (os.execute \"true\"))"))
          (assert.are.equal (.. "t.fnl:2: (macro ..." why)
                            (load-error "{:objects []}\n(macro m [] (io.open \"/etc/passwd\")) (m)"))
          (assert.are.equal (.. "t.fnl:1: (lua ..." why)
                            (load-error "{:objects [] :name (lua \"do end\" \"tostring(os)\")}"))
          (assert.are.equal (.. "t.fnl:1: (import-macros ..." why)
                            (load-error "(import-macros m :x) {:objects []}")))
        (assert.are.equal "t.fnl:1: attempt to call field 'random' (a nil value)"
                          (load-error "{:objects [] :name (tostring (math.random))}"))))

    (it "reports a file that cannot be read"
      (fn []
        (let [(s err) (scene.load-file "no/such/scene.fnl")]
          (assert.is_nil s)
          (assert.are.equal "no/such/scene.fnl: cannot read the scene file: "
                            (err:sub 1 (length "no/such/scene.fnl: cannot read the scene file: "))))
        (let [(s err) (scene.load-file "x.fnl" (fn [] (values nil "nope")))]
          (assert.is_nil s)
          (assert.are.equal "x.fnl: cannot read the scene file: nope" err))))

    (it "uses the file name it was given"
      (fn []
        (assert.are.equal "scenes/bad.fnl:1: objects[1].radius: must be a positive number from 1e-6 to 1e7, got -1"
                          (load-error "{:objects [{:kind :sphere :radius -1}]}" "scenes/bad.fnl"))
        (let [(_ err) (scene.load-string "{:objects [{:kind :sphere :radius -1}]}")]
          (assert.are.equal "scene:1: objects[1].radius: must be a positive number from 1e-6 to 1e7, got -1" err))))))

(describe "scene loader: line numbers in multi-line files"
  (fn []
    (it "points at the line of the offending object field"
      (fn []
        (assert.are.equal "t.fnl:5: objects[2].radius: must be a positive number from 1e-6 to 1e7, got -1"
                          (load-error "{:camera {:pos [0 0 0]
          :fov 60}
 :objects [{:kind :sphere}
           {:kind :sphere
            :radius -1}]}"))))

    (it "points at the line of a bad vector"
      (fn []
        (assert.are.equal
          "t.fnl:3: objects[2].size[2]: must be a positive number from 1e-6 to 1e7, got -1"
          (load-error "{:objects [{:kind :sphere}
           {:kind :box
            :size [1 -1 1]}]}"))
        (assert.are.equal
          "t.fnl:3: objects[2].pos[3]: must be a number from -1e7 to 1e7, got nan"
          (load-error "{:camera {:pos [0 0 0] :pitch 0}
 :objects [{:kind :sphere :pos [0 0 0] :radius 1}
  {:kind :sphere :radius 1 :pos [0 0 (/ 0 0)]}]}"))))

    (it "points at unknown kinds, unknown fields and missing kinds"
      (fn []
        (assert.are.equal
          "t.fnl:2: objects[2].kind: unknown kind :boxx (did you mean :box?) (`love . --kinds` lists them all)"
          (load-error "{:objects [{:kind :sphere}
           {:kind :boxx
            :size [1 1 1]}]}"))
        (assert.are.equal
          "t.fnl:3: objects[2].sise: unknown field (did you mean :size?); known fields: :color :emission :kind :mirror :pos :rotate :roughness :scale :size"
          (load-error "{:objects [{:kind :sphere}
           {:kind :box
            :sise [1 1 1]}]}"))
        (assert.are.equal
          "t.fnl:2: objects[2]: missing :kind (see `love . --kinds` for the list)"
          (load-error "{:objects [{:kind :sphere}
           {:pos [1 1 1]}]}"))))

    (it "points at section fields and top-level fields"
      (fn []
        (assert.are.equal "t.fnl:3: render.epsilon: must be a number from 0 to 10, got -1"
                          (load-error "{:name \"x\"
 :render {:shadows true
          :epsilon -1}
 :objects []}"))
        (assert.are.equal "t.fnl:3: render.glow: must be true or false, got 1"
                          (load-error "{:objects []
 :render {:reflections 3
  :glow 1}}"))
        (assert.are.equal "t.fnl:3: camera.fov: must be a number of degrees from 0.1 to 179, got 0"
                          (load-error "{:objects []
 :camera {:pos [0 0 0]
          :fov 0}}"))
        (assert.are.equal
          "t.fnl:4: environment[3]: must be a colour of three numbers from 0 to 1, got 2"
          (load-error "{:name \"x\"

 :objects []
 :environment [0 0 2]}"))
        (assert.are.equal
          "t.fnl:3: objects: must be a list [...] of objects, not a table with named fields"
          (load-error "{:name \"x\"
 :camera {:pos [0 0 0]}
 :objects {:a 1}}"))))

    ;; Regression: key-line once built a Lua pattern from the field name without
    ;; escaping it, so the '-' in max-steps / draw-distance acted as a quantifier and the
    ;; message fell back to the line of :render (2) instead of the field's (3).
    (it "points at hyphenated fields (max-steps, draw-distance) on their own line"
      (fn []
        (assert.are.equal
          "t.fnl:3: render.max-steps: must be an integer from 1 to 100000, got 1.5"
          (load-error "{:name \"x\"
 :render {:shadows true
          :max-steps 1.5}
 :objects []}"))
        (assert.are.equal
          "t.fnl:3: render.draw-distance: must be a positive number from 1e-6 to 1e7, got -1"
          (load-error "{:name \"x\"
 :render {:shadows true
          :draw-distance -1}
 :objects []}"))))))

(describe "scene loader: no side effects on the host's Fennel"
  (fn []
    ;; A scene whose macro failed to compile used to leave Fennel's in-progress compile
    ;; options (the sandbox env and allowedGlobals) behind; fennel.searcher copies them,
    ;; so the next module it loaded could not see `require`. The loader now refuses
    ;; compile-time forms before compiling.
    (it "leaves fennel.searcher working after a scene with a macro"
      (fn []
        (let [fennel (require :fennel)]
          (assert.is_nil (scene.load-string "(macro m [] (io.open \"x\")) (m)" "t.fnl"))
          (let [loader (fennel.searcher :src.app.cli)
                (ok err) (pcall loader :src.app.cli)]
            (assert (= :function (type loader)))
            (assert (= true ok) (tostring err))))))

    (it "loads valid scenes after any kind of failed one"
      (fn []
        (each [_ bad (ipairs ["{:objects [}" "(os.exit)" "(eval-compiler (os.exit))"
                              "(macro m [] (io.open \"x\")) (m)"
                              "{:objects [] :name (tostring (math.random))}"])]
          (assert.is_nil (scene.load-string bad "t.fnl"))
          (let [s (assert (scene.load-string "{:objects [{:kind :sphere :radius 2}]}" "t.fnl"))]
            (assert.are.equal 2 (. s.objects 1 :radius))))))))

(describe "scene loader: large scenes"
  (fn []
    ;; Timings are not asserted here (CI shares its cores); the figures are in the
    ;; notes of issue 12 and in src/scene/sandbox.fnl's limits.
    (it "loads 100,000 spheres made by a loop within the sandbox's limits"
      (fn []
        (let [s (assert (scene.load-file "test/fixtures/spheres-100000.fnl"))
              first (. s.objects 1)
              last (. s.objects 100000)]
          (assert.are.equal 100000 (length s.objects))
          (assert.are.equal :sphere first.kind)
          (assert.are.equal 100000 last.index)
          ;; Object i sits in its own cell of the 316-wide grid.
          (assert.is_true (and (<= 0 (. first.pos 1) 1) (<= 0 (. first.pos 2) 1)))
          (assert.is_true (and (<= 143 (. last.pos 1) 144) (<= 316 (. last.pos 2) 317)))
          (assert.is_true (<= 0.1 last.radius 0.4)))))

    (it "loads 100,000 boxes built with vector helpers that leave garbage behind"
      (fn []
        (let [s (assert (scene.load-string
                         "(fn hash [i k]
                            (let [h (% (+ (* i 73856093) (* k 19349663) 12345) 1000003)]
                              (/ (% (* h h) 1000003) 1000003)))
                          (fn scale [[x y z] f] [(* x f) (* y f) (* z f)])
                          (fn add [[ax ay az] [bx by bz]] [(+ ax bx) (+ ay by) (+ az bz)])
                          (local points (fcollect [i 0 99999] [(% i 316) (math.floor (/ i 316)) 0]))
                          {:objects (icollect [i p (ipairs points)]
                                      (let [h (+ 1 (* 20 (hash i 1)))]
                                        {:kind :box :pos (add (scale p 4) [0 0 (/ h 2)])
                                         :size (scale [1 1 (/ h 3)] 3)
                                         :color (scale [1 1 1] (+ 0.4 (* 0.4 (hash i 2))))}))}"
                         "city.fnl"))]
          (assert.are.equal 100000 (length s.objects))
          (assert.are.equal :box (. s.objects 100000 :kind))
          (assert.are.same [(* 4 (% 99999 316)) (* 4 (math.floor (/ 99999 316)))]
                           [(. s.objects 100000 :pos 1) (. s.objects 100000 :pos 2)]))))

    (it "copies every vector, as the full check does, so scene tables are not shared"
      (fn []
        (let [s (assert (scene.load-string
                         "(let [p [1 2 3]] {:objects [{:kind :sphere :pos p} {:kind :box :pos p :size p}]})"
                         "t.fnl"))
              [a b] s.objects]
          (assert.are.same [1 2 3] a.pos)
          (assert.are.same [1 2 3] b.size)
          (assert.is_false (rawequal a.pos b.pos))
          (assert.is_false (rawequal b.pos b.size)))))

    (it "gives the full check's message for a vector the quick check does not pass"
      (fn []
        (each [source expected
               (pairs {"{:objects [{:kind :sphere :pos {1 1 2 2 3 3 :w 4}}]}"
                       "t.fnl:1: objects[1].pos: must be a list of three numbers like [1 2 3] with exactly three numbers"
                       "{:objects [{:kind :sphere :pos {1 1 2 2 3 3 1.5 0}}]}"
                       "t.fnl:1: objects[1].pos: must be a list of three numbers like [1 2 3] with exactly three numbers"
                       "{:objects [{:kind :box :size [1 1 (fn [t] 1)]}]}"
                       "t.fnl:1: objects[1].size[3]: must be a positive number from 1e-6 to 1e7, got a function"
                       "{:objects [{:kind :sphere} {:kind :sphere :color [0.5 0.5 1.5]}]}"
                       "t.fnl:1: objects[2].color[3]: must be a colour of three numbers from 0 to 1, got 1.5"})]
          (assert.are.equal expected (load-error source)))))

    (it "refuses what only lowering finds at the node's line, and lowers other trees once, in the plan"
      (fn []
        (assert.are.equal
          "t.fnl:3: objects[1].children[2]: :twist needs a child bounded in x and y (its Lipschitz factor grows with the child's size)"
          (load-error "{:objects [\n {:kind :union :children [{:kind :sphere}\n  {:kind :twist :angle 1\n   :children [{:kind :plane}]}]}]}"))
        ;; Which trees the loader lowers: those holding a twist, a bend or a custom
        ;; node, however deep.
        (let [lower (require :src.sdf.lower)]
          (assert.is_false (lower.may-refuse? {:kind :union :children [{:kind :sphere} {:kind :torus}]}))
          (assert.is_true (lower.may-refuse? {:kind :union :children [{:kind :sphere}
                                                                      {:kind :translate :children [{:kind :bend :children [{:kind :box}]}]}]}))
          (assert.is_true (lower.may-refuse? {:kind :custom})))))))

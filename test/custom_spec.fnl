;; Custom nodes through the app: `love . --probe` on the CPU and with --gpu agree on
;; distance functions written in Fennel (alone, with helpers, piecewise, in loops,
;; under operations), within the budget test/probe_spec.fnl holds the primitives to;
;; --export-shader, --render and the player's hot reload take scenes/custom.fnl.
(local {: lcg} (require :test.support.fields))
(local glslang (. (require :test.support.glslang) :ok?))

(local spacing 12)
(local points-per-node 2000)

;; Each on its own cell of a grid, as in test/probe_spec.fnl.
(local nodes
  [;; A sphere written by hand, its radius a uniform.
   "{:kind :custom :params {:r 1.2} :bounds [1.2 1.2 1.2]
     :distance (fn [x y z r] (- (math.sqrt (+ (* x x) (* y y) (* z z))) r))}"
   ;; A rounded box from helpers, one of them a function of the file.
   "{:kind :custom :params {:w 1 :d 0.7 :h 0.5 :r 0.2} :bounds [1 0.7 0.5] :rotate [10 20 30]
     :distance (fn [x y z w d h r]
                 (fn outside [a] (math.max a 0))
                 (let [qx (- (math.abs x) (- w r)) qy (- (math.abs y) (- d r)) qz (- (math.abs z) (- h r))]
                   (- (+ (len3 (outside qx) (outside qy) (outside qz)) (math.min (math.max qx qy qz) 0)) r)))}"
   ;; A gyroid shell cut by a sphere: measured and divided.
   "{:kind :custom :params {:f 4 :t 0.08} :bounds [1.5 1.5 1.5]
     :distance (fn [x y z f t]
                 (let [g (+ (* (math.sin (* f x)) (math.cos (* f y))) (* (math.sin (* f y)) (math.cos (* f z)))
                            (* (math.sin (* f z)) (math.cos (* f x))))]
                   (math.max (- (math.abs (/ g f)) t) (- (len3 x y z) 1.5))))}"
   ;; Piecewise: a capsule as three cases.
   "{:kind :custom :bounds [0.6 0.6 1.6] :scale 1.3
     :distance (fn [x y z]
                 (if (> z 1) (- (len3 x y (- z 1)) 0.6)
                     (< z -1) (- (len3 x y (+ z 1)) 0.6)
                     (- (math.sqrt (+ (* x x) (* y y))) 0.6)))}"
   ;; A loop: spheres on a ring blended by a smooth minimum.
   "{:kind :custom :bounds [1.4 1.4 0.4]
     :distance (fn [x y z]
                 (var d 100)
                 (for [i 0 5]
                   (let [a (* i 1.0471976)
                         s (- (len3 (- x (math.cos a)) (- y (math.sin a)) z) 0.4)
                         h (math.max (- 0.3 (math.abs (- d s))) 0)]
                     (set d (- (math.min d s) (/ (* h h) 1.2)))))
                 d)}"
   ;; Under operations: a twist (it needs its child's bounds) and a smooth union.
   "{:kind :twist :angle 45 :children [{:kind :custom :bounds [0.6 0.6 1.5]
     :distance (fn [x y z] (math.max (- (math.abs x) 0.6) (- (math.abs y) 0.3) (- (math.abs z) 1.5)))}]}"
   "{:kind :smooth-union :radius 0.3 :children
     [{:kind :custom :pos [-0.5 0 0] :color [1 0 0] :bounds [1 1 1]
       :distance (fn [x y z] (- (len3 x y z) 1))}
      {:kind :sphere :pos [0.7 0 0] :radius 0.8 :color [0 0 1]}]}"])

(fn scene-text []
  (let [side (math.ceil (math.sqrt (length nodes)))
        placed (icollect [i n (ipairs nodes)]
                 (let [k (- i 1)]
                   (.. "{:kind :translate :offset [" (* spacing (% k side)) " "
                       (* spacing (math.floor (/ k side))) " 0] :children [" n "]}")))]
    (values (.. "(fn len3 [a b c] (math.sqrt (+ (* a a) (* b b) (* c c))))\n"
                "{:render {:draw-distance 1000}\n :objects [\n"
                (table.concat placed "\n") "]}\n")
            side)))

(fn points-text [side]
  (let [rand (lcg 29)
        lines []]
    (for [k 0 (- (length nodes) 1)]
      (let [cx (* spacing (% k side)) cy (* spacing (math.floor (/ k side)))]
        (for [_ 1 points-per-node]
          (table.insert lines (string.format "%.6f %.6f %.6f"
                                             (+ cx (* 3 (- (* 2 (rand)) 1)))
                                             (+ cy (* 3 (- (* 2 (rand)) 1)))
                                             (* 3 (- (* 2 (rand)) 1)))))))
    (.. (table.concat lines "\n") "\n")))

(fn write-file [path text]
  (with-open [f (assert (io.open path :wb))] (f:write text)))

(fn read-file [path]
  (with-open [f (assert (io.open path :rb))] (f:read :*a)))

(fn run [command]
  (let [text (with-open [p (io.popen (.. "SDL_VIDEODRIVER=offscreen timeout 300 " command
                                         " 2>&1; echo \"exit:$?\""))]
               (p:read :*a))]
    (values (tonumber (text:match "exit:(%d+)%s*$")) (text:gsub "exit:%d+%s*$" ""))))

(fn parse-lines [text]
  (icollect [line (text:gmatch "[^\n]+")]
    (icollect [w (line:gmatch "%S+")] (tonumber w))))

(describe "custom nodes through the app"
  (fn []
    (os.execute "mkdir -p test/out")
    (let [(text side) (scene-text)
          scene-path "test/out/custom-probe.fnl"
          points-path "test/out/custom-points.txt"]
      (write-file scene-path text)
      (write-file points-path (points-text side))

      (it (.. "the GPU agrees with the CPU at " points-per-node " points per custom node")
        (fn []
          (let [(code cpu-out) (run (.. "love . --probe " scene-path " < " points-path))
                (gcode gpu-out) (run (.. "love . --probe " scene-path " --gpu < " points-path))
                cpu (parse-lines cpu-out)
                gpu (parse-lines gpu-out)]
            (assert.are.equal 0 code cpu-out)
            (assert.are.equal 0 gcode gpu-out)
            (assert.are.equal (* points-per-node (length nodes)) (length cpu))
            (assert.are.equal (length cpu) (length gpu))
            (var worst {:err 0})
            (var colour-flips 0)
            (var near 0)
            (each [i c (ipairs cpu)]
              (let [g (. gpu i)
                    err (/ (math.abs (- (. c 1) (. g 1))) (+ 1 (math.abs (. c 1))))]
                (when (< (math.abs (. c 1)) 0.5) (set near (+ near 1)))
                (when (> err worst.err)
                  (set worst {: err : i :node (math.floor (/ (- i 1) points-per-node))
                              :cpu (. c 1) :gpu (. g 1)}))
                (for [k 2 5]
                  (when (> (math.abs (- (. c k) (. g k))) 1e-3) (set colour-flips (+ colour-flips 1))))))
            (print (string.format "\ncustom probe: %d points (%d within 0.5 of a surface), worst relative distance error %.3g (point %s, node %s: cpu %s gpu %s), %d material channels differ"
                                  (length cpu) near worst.err (tostring worst.i) (tostring worst.node)
                                  (tostring worst.cpu) (tostring worst.gpu) colour-flips))
            ;; The points are not all far away: a tenth at least lies near a surface.
            (assert.is_true (> near (* 0.1 (length cpu))) (.. near " points near a surface"))
            ;; The primitives' budget (test/probe_spec.fnl): float32 rounding of the
            ;; coordinates and a few ulps per operation; the gyroid's sin and cos
            ;; are llvmpipe's float32 ones.
            (assert.is_true (< worst.err 2e-5) (.. "worst error " worst.err " at point " (tostring worst.i)))
            ;; The smooth union's material blend: a hard choice nowhere here.
            (assert.is_true (< colour-flips 20) (.. colour-flips " material channels differ")))))

      (it "--export-shader bakes the custom functions in and compiles as GLSL ES 3.00"
        (fn []
          (let [(code out) (run "love . --export-shader scenes/custom.fnl --out test/out/custom-export.glsl")
                text (read-file "test/out/custom-export.glsl")
                (ok? vout) (glslang (.. "#version 300 es\nprecision highp float;\nprecision highp int;\n"
                                        "uniform vec3 iResolution;\nuniform float iTime;\nout vec4 shadertoyOut;\n"
                                        text "void main() { mainImage(shadertoyOut, gl_FragCoord.xy); }\n"))]
            (assert.are.equal 0 code out)
            (assert.truthy (text:find "float sdCustom1(vec3 p" 1 true))
            (assert.truthy (text:find "sdCustom2Fn0" 1 true))
            (assert.is_true ok? vout))))

      (it "hot reload: a :params edit re-sends uniforms, compiling nothing (the player's own reload path)"
        (fn []
          (let [(code out) (run "love . --soak scenes/custom.fnl --cycles 6")]
            (assert.are.equal 0 code out)
            (assert.truthy (out:find "editing a custom node's :params value changes the next frame without a shader compile: ok" 1 true) out)
            (assert.truthy (out:find "soak checks: 0 failed" 1 true) out))))

      (it "--render draws scenes/custom.fnl"
        (fn []
          (let [(code out) (run "love . --render scenes/custom.fnl --out test/out/custom.png --size 160x90")]
            (assert.are.equal 0 code out)
            (assert.truthy (out:find "wrote test/out/custom.png" 1 true) out)))))))

;; GLSL's functions that Lua's math lacks (math.clamp ...): the translator writes each
;; out in both languages, and here the GPU's float32 evaluation meets the CPU's on a
;; sweep of values. The sweep runs inside the function, over a loop counter, from a
;; :params value: the distance stays |z| - 1 (exact, Lipschitz 1, never divided)
;; plus a small weighted sum of the function's values, so a value the GPU computes
;; differently moves the distance by at least 1e-4, five times the budget. Each
;; function is swept twice: from -4 in steps of 0.25, hitting the edges exactly
;; (integers, halves for round, 0 for sign, the step's edge, mod's multiples), and
;; from -3.99, off them by 0.01 at least (float32 rounding of the start is 1e-7).
(local library-calls
  {:clamp "(math.clamp v -1.5 2.25)"
   :mix "(math.mix 1.5 -2 v)"
   :fract "(math.fract v)"
   :fract-scaled "(math.fract (* v 0.7))"
   :sign "(math.sign v)"
   :step "(math.step 0.5 v)"
   :smoothstep "(math.smoothstep -1 2 v)"
   :round "(math.round v)"
   :mod "(math.mod v 0.75)"
   :mod-negative "(math.mod v -1.25)"
   :huge "(math.min v math.huge (* 1e-29 math.huge))"})

(local library-names ["clamp" "mix" "fract" "fract-scaled" "sign" "step" "smoothstep" "round"
                      "mod" "mod-negative" "huge"])
(local library-starts [-4 -3.99])
(local library-points 16)

(fn library-scene []
  "A scene of one custom node per function and start, on a grid: its text, the
grid's side and each node's label."
  (let [labels []
        placed []
        count (* (length library-names) (length library-starts))
        side (math.ceil (math.sqrt count))]
    (each [_ name (ipairs library-names)]
      (each [_ start (ipairs library-starts)]
        (let [k (length placed)]
          (table.insert labels (.. name " from " start))
          (table.insert placed
                        (.. "{:kind :translate :offset [" (* spacing (% k side)) " "
                            (* spacing (math.floor (/ k side))) " 0] :children [{:kind :custom :bounds [1 1 1.5] :params {:a " start "}\n"
                            "  :distance (fn [x y z a]\n"
                            "              (var acc 0)\n"
                            "              (for [i 0 31] (let [v (+ a (* i 0.25))] (set acc (+ acc (* (+ i 1) " (. library-calls name) ")))))\n"
                            "              (+ (- (math.abs z) 1) (* 1e-4 acc)))}]}")))))
    (values (.. "{:render {:draw-distance 1000}\n :objects [\n" (table.concat placed "\n") "]}\n")
            side labels)))

(describe "custom nodes: GLSL's functions on the GPU and the CPU"
  (fn []
    (os.execute "mkdir -p test/out")
    (it (.. "agree on a sweep of values, each function's (" library-points " points a node, 32 values a point)")
      (fn []
        (let [(text side labels) (library-scene)
              scene-path "test/out/custom-library.fnl"
              points-path "test/out/custom-library-points.txt"
              rand (lcg 31)
              lines []]
          (write-file scene-path text)
          (for [k 0 (- (length labels) 1)]
            (let [cx (* spacing (% k side)) cy (* spacing (math.floor (/ k side)))]
              (for [_ 1 library-points]
                (table.insert lines (string.format "%.6f %.6f %.6f"
                                                   (+ cx (* 0.9 (- (* 2 (rand)) 1)))
                                                   (+ cy (* 0.9 (- (* 2 (rand)) 1)))
                                                   (* 1.4 (- (* 2 (rand)) 1)))))))
          (write-file points-path (.. (table.concat lines "\n") "\n"))
          (let [(code cpu-out) (run (.. "love . --probe " scene-path " < " points-path))
                (gcode gpu-out) (run (.. "love . --probe " scene-path " --gpu < " points-path))
                cpu (parse-lines cpu-out)
                gpu (parse-lines gpu-out)
                worst {}]
            (assert.are.equal 0 code cpu-out)
            (assert.are.equal 0 gcode gpu-out)
            (assert.are.equal (length lines) (length cpu))
            (assert.are.equal (length cpu) (length gpu))
            (each [i c (ipairs cpu)]
              (let [label (. labels (+ 1 (math.floor (/ (- i 1) library-points))))
                    err (/ (math.abs (- (. c 1) (. gpu i 1))) (+ 1 (math.abs (. c 1))))]
                (when (> err (or (. worst label) 0)) (tset worst label err))))
            (let [bad (icollect [_ label (ipairs labels)]
                        (when (>= (or (. worst label) 0) 2e-5)
                          (string.format "%s: %.3g" label (. worst label))))]
              (print (.. "\nGLSL's functions, worst relative distance error per node: "
                         (table.concat (icollect [_ label (ipairs labels)]
                                         (string.format "%s %.2g" label (or (. worst label) 0)))
                                       ", ")))
              (assert.are.same [] bad))))))))

(describe "custom: the main process's check of a worker's Lua text"
  (fn []
    (local custom (require :src.sdf.custom))
    (fn lua-text [lines] (table.concat lines "\n"))

    (it "takes the translator's own text"
      (fn []
        (assert.is_true
         (custom.check-lua
          (lua-text ["local function sdCustom1Fn1(v1, v2) return math.sqrt(v1 * v1 + v2 * v2) end"
                "return function(v1, v2, v3) local v4 = 0 for v5 = 1, 4 do v4 = v4 + sdCustom1Fn1(v1, v5) end return v4 - 1 end"])))))

    (it "takes what the translator writes for GLSL's functions and math.huge: calls of math's functions and inline expressions, no new function"
      (fn []
        (let [fennel (require :fennel)
              translate (require :src.sdf.translate)
              source "(fn [x y z a]
  (var d math.huge)
  (set d (math.min d (math.clamp x a 1) (math.mix x y (* z z)) (math.fract (+ x y)) (math.sign (- y 1))
                   (math.step a x) (math.smoothstep -1 a (* 2 z)) (math.round (* 3 x)) (math.mod x a)))
  d)"
              (_ form) ((fennel.parser (fennel.string-stream source) "t.fnl"))
              t (assert (translate.translate form))]
          (assert.is_true (custom.check-lua t.lua) t.lua)
          (assert.is_true (custom.check-glsl t.glsl t.glsl-name) t.glsl)
          ;; The value check of the text is the same as before: no math function
          ;; other than those it calls by name.
          (assert.falsy (t.lua:find "math%.[%a]+[^%a(]") t.lua))))

    (it "refuses a helper defined again under its name, which its body would call: an endless tail call"
      (fn []
        (assert.is_false
         (not (not (custom.check-lua
                    (lua-text ["local function sdCustom1Fn1(v1) return v1 end"
                          "local function sdCustom1Fn1(v1) return sdCustom1Fn1(v1) end"
                          "return function(v1, v2, v3) return sdCustom1Fn1(v1) end"])))))))

    (it "refuses a function as a value: a helper passed to itself, math's function in a variable"
      (fn []
        (each [_ text (ipairs [(lua-text ["local function sdCustom1Fn1(v1) return v1(v1) end"
                                     "return function(v1, v2, v3) return sdCustom1Fn1(sdCustom1Fn1) end"])
                               (lua-text ["return function(v1, v2, v3) local v4 = math.sqrt return v4(v1) end"])
                               (lua-text ["local function sdCustom1Fn1(v1) return v1 end"
                                     "return function(v1, v2, v3) local v4 = sdCustom1Fn1 return v4(v1) end"])])]
          (assert.is_false (not (not (custom.check-lua text))) text))))))

(describe "custom: a translation the check refuses"
  (fn []
    (it "is said as the check's reason and a translator bug, never as 'table: 0x...'"
      (fn []
        (let [custom (require :src.sdf.custom)
              load (require :src.scene.load)
              real custom.descriptor
              source "{:objects [{:kind :custom :distance (fn [x y z] (- (math.sqrt (+ (* x x) (* y y) (* z z))) 1)) :bounds [1 1 1]}]}"]
          ;; What the check raises when it refuses a text (see custom.descriptor).
          (set custom.descriptor
               (fn [node]
                 (error {:lower-error (.. (tostring node.path) ": a custom node: its Lua is not the translator's (refused)")
                         :reason "a custom node: its Lua is not the translator's (refused)"
                         : node})))
          (let [(ok? scene err) (pcall load.load-string source "t.fnl")]
            (set custom.descriptor real)
            (assert.is_true ok? (tostring scene))
            (assert.is_nil scene)
            (assert.is_nil (err:find "table: 0x" 1 true) err)
            (assert.truthy (err:find "t.fnl:1: objects[1].distance: its translation was refused by the check of the translator's texts (a custom node: its Lua is not the translator's (refused)): a bug in the translator; please report it with this file" 1 true) err)))))))

;; tier: fast
;; The translator from a numeric subset of Fennel to GLSL and Lua
;; (src/sdf/translate.fnl), and custom nodes in the loader (src/sdf/custom.fnl): the
;; Lua it writes computes what Fennel computes, the GLSL validates and holds nothing
;; of the scene's text, every refused construct names itself and its line, and
;; :params are uniforms (a value edit keeps the shader).
(local fennel (require :fennel))
(local translate (require :src.sdf.translate))
(local custom (require :src.sdf.custom))
(local load (require :src.scene.load))
(local plan-mod (require :src.render.plan))
(local codegen (require :src.render.codegen))
(local glslang (. (require :test.support.glslang) :ok?))
(local {: lcg} (require :test.support.fields))

(fn parse [source]
  (let [(_ form) ((fennel.parser (fennel.string-stream source) "t.fnl"))] form))

;; The four shapes of the brief, and the rest of the subset, written with names that
;; must not reach the output (radius-of-ball, my-helper, ...).
(local shapes
  {:sphere {:source "(fn [x y z radius-of-ball]
  (- (math.sqrt (+ (* x x) (* y y) (* z z))) radius-of-ball))"
            :params [1.3]}
   :rounded-box {:source "(fn [x y z half-w half-d half-h corner]
  (fn my-length [a b c] (math.sqrt (+ (* a a) (* b b) (* c c))))
  (fn positive-part [a] (math.max a 0))
  (let [qx (- (math.abs x) (- half-w corner))
        qy (- (math.abs y) (- half-d corner))
        qz (- (math.abs z) (- half-h corner))]
    (- (+ (my-length (positive-part qx) (positive-part qy) (positive-part qz))
          (math.min (math.max qx qy qz) 0))
       corner)))"
                 :params [0.9 0.6 0.5 0.2]}
   :gyroid-ball {:source "(fn [x y z frequency]
  (let [gyroid-value (+ (* (math.sin (* frequency x)) (math.cos (* frequency y)))
                        (* (math.sin (* frequency y)) (math.cos (* frequency z)))
                        (* (math.sin (* frequency z)) (math.cos (* frequency x))))]
    (math.max (- (math.abs (/ gyroid-value frequency)) 0.05)
              (- (math.sqrt (+ (* x x) (* y y) (* z z))) 1))))"
                 :params [4]}
   :piecewise {:source "(fn [x y z]
  (let [flat (math.sqrt (+ (* x x) (* y y)))]
    (if (> z 0.5) (- (math.sqrt (+ (* flat flat) (^ (- z 0.5) 2))) 0.4)
        (< z -0.5) (- (math.sqrt (+ (* flat flat) (^ (+ z 0.5) 2))) 0.4)
        (and (>= z -0.5) (<= z 0.5) (not (> flat 100))) (- flat 0.4)
        1000)))"
               :params []}
   :loop-and-values {:source "(fn [x y z]
  (fn folded [a b] (values (math.abs a) (math.abs b) (% (+ a b) 0.7)))
  (var nearest 100)
  (for [step-index 0 5]
    (let [angle (* step-index 1.0471976)
          (fa fb fc) (folded (- x (math.cos angle)) (- y (math.sin angle)))]
      (when (or (< fa 2) (> fc 0.1))
        (set nearest (math.min nearest (- (math.sqrt (+ (* fa fa) (* fb fb) (* z z))) 0.25))))))
  (for [k 4 1 -2] (set nearest (+ nearest (* k 0.001))))
  (if (< x 0) (set nearest (+ nearest 0.002)) (> x 1) (set nearest (- nearest 0.001)) (set nearest nearest))
  (+ nearest (* 0.001 (-> x (- 1) (/ 2))) (* 0.001 (->> x (- 5) (/ 2))) (* 0.01 (math.atan y x)) (* 0.001 (math.atan x)) (* 0.001 (math.exp (- (math.abs z))))
     (* 0.001 (math.pow (math.abs x) 1.5)) (* 0.001 (math.floor x)) (* 0.001 (math.ceil y))
     (* 0.0001 (/ x)) (- 0.001) (* 0.001 math.pi)))"
                     :params []}
   ;; The sign pattern, GLSL's sign(), and two ifs that only look like it.
   :signs {:source "(fn [x y z]
  (let [side-offset (- x 0.5)
        side (if (> side-offset 0) 1 (< side-offset 0) -1 0)
        half (if (> y 0) 1 (< y 0) -1 0.5)]
    (+ (* side (math.abs z)) (* 0.1 half) (if (> x 0) 1 (< z 0) -1 0) (if (> z 0) 1 (< z 0) -1 0))))"
           :params []}
   ;; GLSL's functions Lua's math lacks (math.clamp ...), math.huge, and helpers
   ;; defined inside helpers, which must be written out before their callers.
   :library {:source "(fn [x y z low-edge]
  (fn outer-helper [a]
    (fn inner-helper [b] (* b 2))
    (+ (inner-helper a) 1))
  (var nearest math.huge)
  (for [k 0 2] (set nearest (math.min nearest (- (math.abs (- z k)) 0.3))))
  (+ nearest
     (* 0.01 (math.clamp (* 2 x) low-edge 0.5)) (* 0.01 (math.mix x (* y y) (math.fract (+ x y))))
     (* 0.01 (math.fract (* 3 x))) (* 0.01 (math.sign (- y 0.25))) (* 0.01 (math.step low-edge x))
     (* 0.01 (math.smoothstep -0.5 (+ 1 low-edge) (- y x))) (* 0.01 (math.round (* 2.5 y)))
     (* 0.01 (math.mod (- x z) 0.7)) (* 0.01 (math.mod x (- 1.5))) (* 0.01 (outer-helper y))
     (math.clamp 2 0 1) (* 1e-32 math.huge)))"
             :params [-0.3]}
   ;; Several values in var and set: a swap reads both before it writes.
   :several-vars {:source "(fn [x y z]
  (fn sum-and-difference [a b] (values (+ a b) (- a b)))
  (var (total rest) (sum-and-difference x y))
  (set (total rest) (values rest total))
  (set (total rest) (sum-and-difference total 1))
  (var (r s) (values 1 2))
  (set (r s) (values s (+ r z)))
  (+ total (* 2 rest) (* 3 r) (* 5 s)))"
                  :params []}})

(local shape-names ["sphere" "rounded-box" "gyroid-ball" "piecewise" "loop-and-values" "signs"
                    "library" "several-vars"])

;; GLSL's functions as the reference computes them, from their GLSL definitions
;; (round as floor(x + 0.5), the translator's choice at .5), and math.huge as the
;; translator writes it (GLSL has no infinity).
(local glsl-library
  {:clamp (fn [x lo hi] (math.min (math.max x lo) hi))
   :mix (fn [a b t] (+ (* a (- 1 t)) (* b t)))
   :fract (fn [x] (- x (math.floor x)))
   :sign (fn [x] (if (> x 0) 1 (< x 0) -1 0))
   :step (fn [edge x] (if (< x edge) 0 1))
   :smoothstep (fn [e0 e1 x]
                 (let [t (math.min (math.max (/ (- x e0) (- e1 e0)) 0) 1)]
                   (* t t (- 3 (* 2 t)))))
   :round (fn [x] (math.floor (+ x 0.5)))
   :mod (fn [x y] (- x (* y (math.floor (/ x y)))))
   :huge 1e30})

;; Names of the scene's text that may appear in no output.
(local scene-names ["radius" "ball" "half" "corner" "my" "positive" "gyroid" "frequency" "low" "edge" "outer" "inner" "total" "rest" "sum"
                    "flat" "folded" "nearest" "step" "angle" "fa" "fb" "fc"])

;; What a GLSL identifier of the output may be: a generated name or GLSL's own.
(local glsl-words (collect [_ w (ipairs ["float" "vec2" "vec3" "vec4" "int" "bool" "return" "if"
                                         "else" "for" "p" "x" "y" "z" "w" "sqrt" "abs" "floor"
                                         "ceil" "sin" "cos" "tan" "asin" "acos" "atan" "exp"
                                         "log" "pow" "min" "max" "mod" "length" "sign"])]
                    w true))

(fn glsl-tokens [text]
  "Identifiers and numbers of `text`, in order: [{:kind :word|:number :text}]."
  (let [out []]
    (var i 1)
    (while (<= i (length text))
      (let [c (text:sub i i)]
        (if (c:match "[%a_]")
            (let [word (text:match "^[%w_]+" i)]
              (table.insert out {:kind :word :text word})
              (set i (+ i (length word))))
            (or (c:match "%d") (and (= c ".") (: (text:sub (+ i 1) (+ i 1)) :match "%d")))
            (let [n (or (text:match "^[%d%.]+[eE][-+]?%d+" i) (text:match "^[%d%.]+" i))]
              (table.insert out {:kind :number :text n})
              (set i (+ i (length n))))
            (set i (+ i 1)))))
    out))

(fn fennel-function [source]
  "The function Fennel itself makes of `source`, with math in reach. LuaJIT's
math.atan ignores a second argument; Lua 5.3's takes it as atan(y, x), and so does the
translation (GLSL's atan(y, x)): the reference gets 5.3's."
  (let [m (collect [k v (pairs math)] k v)]
    (set m.atan (fn [y ?x] (if ?x ((or math.atan2 math.atan) y ?x) (math.atan y))))
    (each [k v (pairs glsl-library)] (tset m k v))
    (fennel.eval source {:env {:math m} :correlate true})))

(describe "translate"
  (fn []
    (each [_ name (ipairs shape-names)]
      (let [shape (. shapes name)]
        (it (.. name ": the same text every time, made of generated names and decimal numbers")
          (fn []
            (let [a (assert (translate.translate (parse shape.source)))
                  b (assert (translate.translate (parse shape.source)))]
              (assert.are.equal a.glsl b.glsl)
              (assert.are.equal a.lua b.lua)
              ;; A loop's int counter is the one place for whole numbers.
              (each [_ tok (ipairs (glsl-tokens (a.glsl:gsub "for %(int [^\n]*" "")))]
                (if (= tok.kind :number)
                    (assert.truthy (tok.text:find "." 1 true) (.. "a number without a decimal point: " tok.text))
                    (assert.truthy (or (. glsl-words tok.text) (tok.text:match "^v%d+$")
                                       (tok.text:match "^i%d+$") (tok.text:match "^sdCustom[%w]*$"))
                                   (.. "not a generated name: " tok.text))))
              (each [_ word (ipairs scene-names)]
                (assert.falsy (a.glsl:find word 1 true) (.. "the GLSL holds `" word "`"))
                (assert.falsy (a.lua:find word 1 true) (.. "the Lua holds `" word "`"))))))

        (it (.. name ": the main process's checks take both texts")
          (fn []
            (let [t (assert (translate.translate (parse shape.source)))]
              (assert.is_true (custom.check-lua t.lua) t.lua)
              (assert.is_true (custom.check-glsl t.glsl t.glsl-name) t.glsl))))

        (it (.. name ": the GLSL validates")
          (fn []
            (let [t (assert (translate.translate (parse shape.source)))
                  args (table.concat (fcollect [i 1 (+ (length shape.params) 1)] ", 1.0") "")
                  (ok? out) (glslang (.. "#version 120\n" t.glsl
                                         "\nvoid main() { gl_FragColor = vec4(sdCustom(gl_FragCoord.xyz"
                                         args ")); }\n"))]
              (assert.is_true ok? (.. out "\n" t.glsl)))))

        (it (.. name ": the Lua computes what Fennel computes, at 2000 points")
          (fn []
            (let [t (assert (translate.translate (parse shape.source)))
                  mine (translate.compile-lua t.lua)
                  theirs (fennel-function shape.source)
                  unpack (or table.unpack _G.unpack)
                  rand (lcg 5)]
              (for [_ 1 2000]
                (let [x (* 3 (- (* 2 (rand)) 1)) y (* 3 (- (* 2 (rand)) 1)) z (* 3 (- (* 2 (rand)) 1))
                      want (theirs x y z (unpack shape.params))
                      args [x y z (unpack shape.params)]
                      _ (table.insert args 1)
                      got (mine (unpack args))]
                  ;; The same operations in the same order, but (^ a 2) is a * a here
                  ;; and pow in Lua: one rounding apart at most.
                  (assert.is_true (<= (math.abs (- got want)) (* 1e-12 (+ 1 (math.abs want))))
                                  (string.format "at %g %g %g: translated %.17g, Fennel %.17g"
                                                 x y z got want)))))))))

    (it "multiplies by the scale argument, and leaves it out when asked"
      (fn []
        (let [t (assert (translate.translate (parse "(fn [x y z] (- x 1))")))
              f (translate.compile-lua t.lua)
              plain (assert (translate.translate (parse "(fn [x y z] (- x 1))") {:scale? false}))]
          (assert.are.equal 1.5 (f 4 0 0 0.5))
          (assert.are.equal 3 ((translate.compile-lua plain.lua) 4 0 0))
          (assert.truthy (plain.glsl:find "float sdCustom(vec3 p) {" 1 true) plain.glsl))))

    (it "writes a chained comparison's middle operand once: its text grows with the links, not doubles"
      (fn []
        ;; Each link's if is the middle operand of the next link's chain. Written out
        ;; twice, 13 links wrote 297 KB of GLSL and 16 were refused as a translator bug.
        (fn nested [n]
          (var e "x")
          (for [_ 1 n] (set e (.. "(if (< y " e " z) x y)")))
          (.. "(fn [x y z] (- (math.sqrt (+ (* x x) (* y y) (* z z))) 1 (* 0.001 " e ")))"))
        (let [t10 (assert (translate.translate (parse (nested 10))))
              t40 (assert (translate.translate (parse (nested 40))))
              f (translate.compile-lua t40.lua)
              fennel-f (fennel.eval (nested 40))]
          ;; Linear: 30 more links add about as much again as the first 10 wrote.
          (assert.is_true (< (length t40.glsl) (* 5 (length t10.glsl)))
                          (.. (length t10.glsl) " and " (length t40.glsl) " bytes"))
          (each [_ [x y z] (ipairs [[0.3 -0.2 0.5] [-0.7 0.1 0.05] [0.2 0.9 -0.4]])]
            (assert.are.equal (fennel-f x y z) (f x y z 1)))
          (let [(ok? out) (glslang (.. "#version 120\n" t40.glsl
                                       "\nvoid main() { gl_FragColor = vec4(sdCustom(gl_FragCoord.xyz, 1.0)); }\n"))]
            (assert.is_true ok? out)))))

    (it "refuses a function whose GLSL text is over its budget, saying so (not as a translator bug)"
      (fn []
        (let [saved translate.limits.text
              source "(fn [x y z] (let [a [[1 2 3] [4 5 6] [7 8 9] [1 3 5]]] (var t 0) (for [i 1 4] (set t (+ t (. (. a i) 1) (. (. a (+ 1 (% i 4))) 2)))) (- x t)))"
              whole (assert (translate.translate (parse source)))]
          ;; Its translation is some KB; half of it as the budget.
          (set translate.limits.text (math.floor (/ (length whole.glsl) 2)))
          (let [(ok? t msg line) (pcall translate.translate (parse source))]
            (set translate.limits.text saved)
            (assert.is_true ok? (tostring t))
            (assert.is_nil t)
            (assert.are.equal 1 line)
            (assert.truthy (msg:find "^its translation is %d+ KB of GLSL, more than %d+ KB") msg)))))

    (it "inlines the numbers and math functions named outside the function"
      (fn []
        (let [t (assert (translate.translate (parse "(fn [x y z] (- (sqrt (* x x)) big-r))")
                                             {:resolve #(case $ :sqrt {:math :sqrt} :big-r {:number 2.5})}))]
          (assert.truthy (t.glsl:find "sqrt((v0 * v0)) - 2.5" 1 true) t.glsl)
          (assert.falsy (t.glsl:find "big" 1 true)))))

    (it "refuses each construct outside the subset with its line and a clear reason"
      (fn []
        (each [_ [source line expected]
               (ipairs [["(fn [x y z]\n (while true 1)\n 1)" 2 "`while` is not supported in a distance function (use for with constant bounds; supported: "]
                        ["(fn [x y z]\n (each [_ v (ipairs [1])] v) 1)" 2 "`each` is not supported"]
                        ["(fn [x y z] \"s\")" 1 "a string is not supported in a distance function"]
                        ["(fn [x y z]\n\n {:a x})" 3 "a {...} table is not supported"]
                        ["(fn [x y z] [x y])" 1 "a distance function must give a number, not a vector of 2 numbers; take (length v) or a component (. v 1)"]
                        ["(fn [x y z] (fn again [a] (again a)) (again x))" 1 "`again` calls itself: recursion is not supported"]
                        ["(fn me [x y z] (me x y z))" 1 "`me` calls itself"]
                        ["(fn [x y z] (print x))" 1 "`print` is not a function a distance function may call (it may call math.sqrt abs"]
                        ["(fn [x y z] (- x some-global))" 1 "`some-global` is not defined in the distance function"]
                        ["(fn [x y z] (math.random))" 1 "`math.random` is not one of the math functions"]
                        ["(fn [x y z] (math.fmod x 1))" 1 "`math.fmod` is not one of the math functions a distance function may use; for a remainder write (% a b) or (math.mod a b), floored as GLSL's mod (math.fmod truncates toward zero)"]
                        ["(fn [x y z] (math.cos2 x 1))" 1 "`math.cos2` is not one of the math functions a distance function may use; did you mean math.cos? (it may use math.sqrt abs floor ceil sin cos tan asin acos atan exp log pow min max, GLSL's clamp mix fract sign step smoothstep round mod, of vectors length dot cross normalize, and math.pi huge)"]
                        ["(fn [x y z] (math.clmap x 0 1))" 1 "`math.clmap` is not one of the math functions a distance function may use; did you mean math.clamp? (it may use "]
                        ["(fn [x y z] (math.frac x))" 1 "GLSL's fract is (math.fract x)"]
                        ["(fn [x y z] (math.lerp x y 0.5))" 1 "GLSL's mix is (math.mix a b t)"]
                        ["(fn [x y z] (math.smothstep 0 1 x))" 1 "did you mean math.smoothstep?"]
                        ["(fn [x y z] (math.huge))" 1 "`math.huge` is a value, not a function a distance function can call"]
                        ["(fn [x y z] (math.clamp x 0))" 1 "math.clamp takes 3 arguments (math.clamp x lo hi), got 2"]
                        ["(fn [x y z] (math.fract x y))" 1 "math.fract takes 1 argument (math.fract x), got 2"]
                        ["(fn [x y z] (math.mod 1 0))" 1 "the number nan is not finite"]
                        ["(fn [x y z] (+ x (math.step 0 x)) (math.mix))" 1 "math.mix takes 3 arguments (math.mix a b t), got 0"]
                        ["(fn [x y z] (var a 1) (fn bump [] (set a 2) 1) (bump))" 1 "closures over mutable state are not supported"]
                        ["(fn [x y z] (let [f (fn [a] (+ a x))] (f 1)))" 1 "a helper function uses `x` of the function around it; pass it as an argument"]
                        ["(fn [x y z] (for [i 1 65] 1) x)" 1 "a for loop may turn at most 64 times, this one turns 65 times"]
                        ["(fn [x y z] (for [i 1 x] 1) x)" 1 "a for loop's bounds must be whole constant numbers"]
                        ["(fn [x y z] (for [i 1 2 0] 1) x)" 1 "never ends"]
                        ["(fn [x y z]\n (if (< x 0) 1))" 2 "an if needs an else branch"]
                        ["(fn [x y z] (if x 1 2))" 1 "a condition must be a comparison"]
                        ["(fn [x y z] (+ (< x 1) 2))" 1 "a comparison is used as a number"]
                        ["(fn [x y z] (and x y))" 1 "a condition must be a comparison"]
                        ["(fn [x y z] (values x y))" 1 "a distance function must give one number, this one gives 2 values"]
                        ["(fn [x y z] (set x 1) x)" 1 "set needs a var declared in the function"]
                        ["(fn [x y] x)" 1 "a distance function takes the point first: (fn [x y z] ...)"]
                        ["(fn [x y z & rest] x)" 1 "rest parameters (&) are not supported"]
                        ["(fn [x y z] (^ x 0.5))" 1 "(^ a n) needs a whole constant n from 0 to 8"]
                        ["(fn [x y z] (let [[a b] x] a))" 1 "a [...] pattern takes a vector or an array apart; this value is a number"]
                        ["(fn [x y z] (let [(a b) (values x)] a))" 1 "binds 2 names to 1 values"]
                        ["(fn [x y z] (var (a b) (values x y z)) a)" 1 "binds 2 names to 3 values"]
                        ["(fn [x y z] (var a 1) (set (a x) (values 1 2)) a)" 1 "set needs a var declared in the function (var x ...)"]
                        ["(fn [x y z] (/ 1 0))" 1 "the number inf is not finite"]
                        ["(fn [x y z] (math.atan x y z))" 1 "math.atan takes 1 or 2 arguments (atan y x), got 3"]
                        ["(fn [x y z] (length x))" 1 "(length v) takes vectors; its argument 1 is a number; for a number use (math.abs x)"]
                        ["(fn [x y z] (#(+ $ 1) x))" 1 "a call needs a function name first"]
                        ["#(+ $1 1)" 1 "a distance function must be written (fn [x y z] ...)"]])]
          (let [(ok? msg got-line) (translate.translate (parse source))]
            (assert.is_nil ok? source)
            (assert.truthy (msg:find expected 1 true) (.. source "\n=> " (tostring msg)))
            (assert.are.equal line got-line (.. source ": line"))))))

    (it "writes the GLSL and the CPU function of the primitives given as :fennel text"
      (fn []
        (let [primitives (require :src.sdf.primitives)
              torus (primitives.lookup :torus)
              capsule (primitives.lookup :capsule)]
          (assert.is_string torus.fennel)
          (assert.truthy (torus.glsl:find "float sdTorus(vec3 p, float a0, float a1) {" 1 true) torus.glsl)
          (assert.truthy (capsule.glsl:find "float sdCapsule(vec3 p, vec3 a0, vec3 a1, float a2) {" 1 true)
                         capsule.glsl)
          ;; On the ring circle's far side, 0.5 out: 0.5 less the tube.
          (assert.are.near 0.25 (torus.cpu 0 -1.5 0 1 0.25) 1e-12)
          (assert.are.near 0.7 (capsule.cpu 0 0 2 0 0 -0.5 0 0 1 0.3) 1e-12))))

    (it "writes GLSL's sign() for (if (> x 0) 1 (< x 0) -1 0) of one name x, and only there"
      (fn []
        (let [t (assert (translate.translate (parse shapes.signs.source)))
              (_ n) (t.glsl:gsub "sign%(" "")]
          (assert.are.equal 2 n t.glsl)
          ;; Zeros too, which random points never hit: sign(0) is 0.
          (each [_ [x y z] (ipairs [[0.5 0 0] [0 0 0] [0.5 1 -2] [1 -1 2] [0 0 -3]])]
            (assert.are.equal ((fennel-function shapes.signs.source) x y z)
                              ((translate.compile-lua t.lua) x y z 1))))))

    (it "refuses a function too costly for the shader"
      (fn []
        (let [(ok? msg) (translate.translate
                         (parse "(fn [x y z] (var a 0) (for [i 1 64] (for [j 1 64] (set a (+ a (* i j))))) a)"))]
          (assert.is_nil ok?)
          (assert.truthy (msg:find "operations per point" 1 true) msg))))))

(fn scene-with [params ?body]
  ;; Bounds that hold a ball of radius up to 2.2 (the loader checks them).
  (.. "{:objects [{:kind :custom :bounds [2.2 2.2 2.2] :params " params "\n"
      " :distance (fn [x y z r] " (or ?body "(- (math.sqrt (+ (* x x) (* y y) (* z z))) r)") ")}]}"))

(describe "custom nodes in the loader"
  (fn []
    (it "a value in :params is a uniform: the shader stays; an edit of the body changes it"
      (fn []
        (let [plan-of #(assert (plan-mod.scene->plan (assert (load.load-string $ "t.fnl"))))
              a (plan-of (scene-with "{:r 1}"))
              b (plan-of (scene-with "{:r 2}"))
              c (plan-of (scene-with "{:r 1}" "(- (math.sqrt (+ (* x x) (* y y) (* z z))) r 0.1)"))]
          (assert.are.equal a.key b.key)
          (assert.are.equal (codegen.shader a) (codegen.shader b))
          (assert.are_not.equal a.key c.key))))

    (it "a (param ...) slider in :params is a value edit too (scenes/custom.fnl's shell)"
      (fn []
        (let [a (assert (load.load-file "scenes/custom.fnl"))
              b (assert (load.load-file "scenes/custom.fnl" nil {:overrides {:shell {:value 0.15 :base 0.06}}}))
              pa (assert (plan-mod.scene->plan a))
              pb (assert (plan-mod.scene->plan b))]
          (assert.are.equal 0.06 (. a.objects 2 :tree :params :thickness))
          (assert.are.equal 0.15 (. b.objects 2 :tree :params :thickness))
          (assert.are.equal pa.key pb.key))))

    (it "gives scenes/custom.fnl the same shader text on every load, none of its names in it"
      (fn []
        (let [shader-of #(codegen.shader (assert (plan-mod.scene->plan (assert (load.load-file "scenes/custom.fnl")))))
              a (shader-of)
              b (shader-of)]
          (assert.are.equal a b)
          (each [_ word (ipairs ["freq" "thickness" "outside" "len3" "shell"])]
            (assert.falsy (a:find word 1 true) (.. "the shader holds `" word "`"))))))

    (it "names one GLSL function per distinct function, in the order met"
      (fn []
        (let [s (assert (load.load-string "(local ball (fn [x y z] (- (math.sqrt (+ (* x x) (* y y) (* z z))) 1)))
{:objects [{:kind :custom :bounds [1 1 1] :distance ball :pos [3 0 0]}
           {:kind :custom :bounds [1 1 1] :distance (fn [x y z] (- (math.max (math.abs x) (math.abs y) (math.abs z)) 1))}
           {:kind :custom :bounds [1 1 1] :distance ball}]}" "t.fnl"))
              names (icollect [_ o (ipairs s.objects)] o.tree.custom.glsl-name)]
          (assert.are.same ["sdCustom1" "sdCustom2" "sdCustom1"] names))))

    (it "packs each node's own parameters when two functions differ only in their names"
      (fn []
        (let [s (assert (load.load-string "{:objects [
  {:kind :custom :bounds [2 2 2] :params {:r 1} :distance (fn [x y z r] (- (math.max (math.abs x) (math.abs y) (math.abs z)) r))}
  {:kind :custom :bounds [2 2 2] :params {:radius 2} :distance (fn [x y z radius] (- (math.max (math.abs x) (math.abs y) (math.abs z)) radius))}]}" "t.fnl"))
              packs (icollect [_ o (ipairs s.objects)]
                      (let [d (custom.descriptor o.tree)] (. (d.pack o.tree) 1)))]
          (assert.are.same [1 2] packs))))

    (it "translates a function of the file the distance function calls, as its helper"
      (fn []
        (let [s (assert (load.load-string "(local {: sqrt} math)
(local lift 0.5)
(fn len3 [a b c] (sqrt (+ (* a a) (* b b) (* c c))))
{:objects [{:kind :custom :bounds [1 1 1.5] :distance (fn [x y z] (- (len3 x y (- z lift)) 1))}]}" "t.fnl"))
              c (. s.objects 1 :tree :custom)
              f (translate.compile-lua c.lua)]
          (assert.truthy (c.glsl:find "float sdCustom1Fn0(float" 1 true) c.glsl)
          (assert.are.equal 1 (f 0 0 2.5 1)))))

    (it "finds hyphenated names of the file (Fennel's Lua name of sd-box is sd_box), and the last of two locals of one name"
      (fn []
        (let [s (assert (load.load-string "(local half-size 1)
(local r 1)
(local r 2)
(fn sd-box [x y z s] (- (math.max (math.abs x) (math.abs y) (math.abs z)) s))
{:objects [{:kind :custom :bounds [3 3 3] :distance (fn [x y z] (- (sd-box x y z half-size) r))}]}" "t.fnl"))
              c (. s.objects 1 :tree :custom)]
          (assert.are.equal -1 ((translate.compile-lua c.lua) 2 0 0 1)))))

    (it "writes a function of the file that calls another before its caller (both texts pass the main process's checks)"
      (fn []
        (let [s (assert (load.load-string "(fn len3 [x y z] (math.sqrt (+ (* x x) (* y y) (* z z))))
(fn sph [x y z r] (- (len3 x y z) r))
{:objects [{:kind :custom :bounds [1 1 1] :distance (fn [x y z] (sph x y z 1))}]}" "t.fnl"))
              c (. s.objects 1 :tree :custom)]
          (assert.is_true (< (assert (c.glsl:find "float sdCustom1Fn1(" 1 true)) (assert (c.glsl:find "float sdCustom1Fn0(" 1 true))) c.glsl)
          (assert.are.equal 1 ((translate.compile-lua c.lua) 0 0 2 1))
          (assert.is_true (custom.check-lua c.lua) c.lua)
          (assert.is_true (custom.check-glsl c.glsl c.glsl-name) c.glsl))))

    (it "takes GLSL's functions destructured from math, and math.huge from outside the function"
      (fn []
        (let [s (assert (load.load-string "(local {: clamp : smoothstep : huge} math)
(local {: mod} math)
;; (mod x 0.3) jumps by 0.003 at every x = 0.3 k: taken on trust.
{:objects [{:kind :custom :bounds [1 1 1] :lipschitz 1 :trust-lipschitz true
  :distance (fn [x y z] (math.max (- (math.max (math.abs x) (math.abs y)) 0.9)
                                  (math.min huge (+ (- (math.abs z) 0.5) (* 0.01 (+ (clamp x 0 1) (smoothstep 0 1 y) (mod x 0.3)))))))}]}" "t.fnl"))
              f (translate.compile-lua (. s.objects 1 :tree :custom :lua))]
          ;; mod is GLSL's (floored), not LuaJIT's math.mod (fmod, truncated).
          (assert.are.near (+ 0.5 (* 0.01 (+ 0 0.5 0.05))) (f -0.25 0.5 1 1) 1e-12))))

    (it "says why a function of the file cannot be read, and what to call instead"
      (fn []
        (let [(ok? msg) (load.load-string "(local fract #(- $ (math.floor $)))
{:objects [{:kind :custom :bounds [1 1 1] :distance (fn [x y z] (- (fract x) 1))}]}" "t.fnl")]
          (assert.is_nil ok?)
          (assert.are.equal "t.fnl:2: objects[1].distance: `fract` is a function the translator cannot read: it has no (fn ...) form in the scene file (a #(...) has none); write it (fn fract [a b] ...); or call math.fract, GLSL's fract" msg))
        (let [(ok? msg) (load.load-string "(local {: fmod} math)
{:objects [{:kind :custom :bounds [1 1 1] :distance (fn [x y z] (- (fmod x 1) 1))}]}" "t.fnl")]
          (assert.is_nil ok?)
          (assert.truthy (msg:find "`fmod` is math.fmod, which a distance function cannot use; for a remainder write (% a b)" 1 true) msg))))

    (it "translates a function made by another one, each closure with its own numbers"
      (fn []
        (let [s (assert (load.load-string "(fn make-ball [r]
  (fn [x y z] (- (math.sqrt (+ (* x x) (* y y) (* z z))) r)))
{:objects [{:kind :custom :bounds [1 1 1] :distance (make-ball 1)}
           {:kind :custom :bounds [2 2 2] :distance (make-ball 2)}]}" "t.fnl"))
              [a b] (icollect [_ o (ipairs s.objects)] o.tree.custom)]
          (assert.are.same ["sdCustom1" "sdCustom2"] [a.glsl-name b.glsl-name])
          (assert.are.equal -1 ((translate.compile-lua a.lua) 0 0 0 1))
          (assert.are.equal -2 ((translate.compile-lua b.lua) 0 0 0 1)))))

    (it "measures the Lipschitz factor: 1 for an exact distance, more for a gyroid"
      (fn []
        (let [exact (assert (load.load-string (scene-with "{:r 1}") "t.fnl"))
              gyroid (assert (load.load-string "{:objects [{:kind :custom :bounds [1 1 1]
 :distance (fn [x y z] (math.max (- (math.abs (+ (* (math.sin (* 4 x)) (math.cos (* 4 y))) (* (math.sin (* 4 y)) (math.cos (* 4 z))) (* (math.sin (* 4 z)) (math.cos (* 4 x))))) 0.2)
                                 (- (math.sqrt (+ (* x x) (* y y) (* z z))) 1)))}]}" "t.fnl"))
              g (. gyroid.objects 1 :tree)]
          (assert.are.equal 1 (. exact.objects 1 :tree :lipschitz))
          ;; sin(4x)cos(4y) + ...: the gradient's length reaches 4 * sqrt(3) = 6.93
          ;; where all three terms agree; the sample finds it within 1%.
          (assert.is_true (< 6.85 g.custom.measured 6.93) (tostring g.custom.measured))
          (assert.are.near (* 1.1 g.custom.measured) g.lipschitz 1e-9))))

    (it "measures GLSL's functions as the shader computes them (smoothstep's slope)"
      (fn []
        (let [smooth (assert (load.load-string "{:objects [{:kind :custom :bounds [1 1 1]
 :distance (fn [x y z] (math.max (- (math.max (math.abs x) (math.abs y)) 0.9) (- (math.abs z) (math.smoothstep -1 1 x))))}]}" "t.fnl"))
              node (. smooth.objects 1 :tree)]
          ;; smoothstep(-1, 1, x) rises fastest at x = 0, by 1.5 / 2: with |z|'s 1,
          ;; a gradient of length sqrt(1 + 0.75^2) = 1.25, divided with the margin.
          (assert.is_true (< 1.24 node.custom.measured 1.2501) (tostring node.custom.measured))
          (assert.are.near (* 1.1 node.custom.measured) node.lipschitz 1e-9))))

    (it "takes a declared :lipschitz at least the measured one, and refuses a smaller one"
      (fn []
        (let [ok (assert (load.load-string "{:objects [{:kind :custom :bounds [1 1 1] :lipschitz 3
 :distance (fn [x y z] (- (* 2 (math.max (math.abs x) (math.abs y) (math.abs z))) 1))}]}" "t.fnl"))
              (bad msg) (load.load-string "{:objects [{:kind :custom :bounds [1 1 1] :lipschitz 1.5
 :distance (fn [x y z] (- (* 2 (math.max (math.abs x) (math.abs y) (math.abs z))) 1))}]}" "t.fnl")]
          (assert.are.equal 3 (. ok.objects 1 :tree :lipschitz))
          (assert.is_nil bad)
          (assert.truthy (msg:find "t.fnl:1: objects[1].lipschitz: declares 1.5, but the distance changes by 2 per unit" 1 true) msg))))

    (it "divides the distance by the factor, on the CPU as on the GPU (one argument)"
      (fn []
        (let [s (assert (load.load-string "{:objects [{:kind :custom :bounds [1 1 1]
 :distance (fn [x y z] (- (* 3 (math.max (math.abs x) (math.abs y) (math.abs z))) 1))}]}" "t.fnl"))
              node (. s.objects 1 :tree)
              desc (custom.descriptor node)
              args (desc.pack node)]
          (assert.are.near (/ 1 (* 1.1 3)) (. args 1) 1e-6)
          (assert.are.near (/ 2 (* 1.1 3)) (desc.cpu 1 0 0 (. args 1)) 1e-6))))

    (it "animates a parameter given as a function of time (its values declared: issue 43)"
      (fn []
        (let [s (assert (load.load-string (scene-with "{:r (fn [t] (+ 1 t))} :ranges {:r [1 2]}") "t.fnl"))]
          (assert.is_true (load.animated? s))
          (assert.are.equal 1 (. s.objects 1 :tree :params :r))
          (assert.is_true (load.animate s 0.5))
          (assert.are.equal 1.5 (. s.objects 1 :tree :params :r)))))

    (it "the main process refuses texts the translator would not write (a forged worker answer)"
      (fn []
        (let [s (assert (load.load-string (scene-with "{:r 1}") "t.fnl"))
              node (. s.objects 1 :tree)
              good node.custom
              forge (fn [field from to]
                      (let [c (collect [k v (pairs good)] k v)
                            (text n) (: (. c field) :gsub from to 1)]
                        (assert.are.equal 1 n (.. "the forgery of " field " did not apply: " from))
                        (tset c field text)
                        (when (= field :glsl) (set c.key (custom.digest text)))
                        (doto (collect [k v (pairs node)] k v) (tset :custom c))))
              refused (fn [n]
                        (let [(ok? e) (pcall custom.descriptor n)]
                          (and (not ok?) (= (type e) :table) e.reason)))]
          (assert.truthy (custom.descriptor node))
          (each [_ [field from to why]
                 (ipairs [[:lua "math%.sqrt" "os.exit" "not the translator's"]
                          [:lua "return %(" "return (\"x\" .. " "not the translator's"]
                          [:lua "return function%(([^)]*)%)" "return function(%1) while true do end" "not the translator's"]
                          [:lua "return function%(([^)]*)%)" "return function(%1) for v99 = 1, 1000 do end" "not the translator's"]
                          [:lua "math%.sqrt" "string.rep" "not the translator's"]
                          [:glsl "length" "texture2D" "not the translator's"]
                          [:glsl "return " "for (int i9 = 0; i9 <= 100000; i9++) {} return " "not the translator's"]])]
            (let [why-got (refused (forge field from to))]
              (assert.truthy (and why-got (why-got:find why 1 true)) (.. field " " to ": " (tostring why-got)))))
          ;; The digest must match the GLSL the key stands for.
          (let [c (collect [k v (pairs good)] k v)]
            (set c.key "00000000000000-1")
            (assert.truthy (: (refused (doto (collect [k v (pairs node)] k v) (tset :custom c))) :find
                              "digest" 1 true))))))

    (it "works under operations and with the shorthands"
      (fn []
        (let [s (assert (load.load-string "{:objects [{:kind :smooth-union :radius 0.3 :children
 [{:kind :custom :bounds [1 1 1] :pos [1 0 0] :rotate [0 0 30] :scale 1.5 :color [1 0 0]
   :distance (fn [x y z] (- (math.sqrt (+ (* x x) (* y y) (* z z))) 1))}
  {:kind :sphere}]}]}" "t.fnl"))
              plan (assert (plan-mod.scene->plan s))
              (ok? out) (glslang (codegen.shader plan :core))]
          (assert.is_true ok? out))))))

;; Custom nodes: a scene's own distance function, {:kind :custom :distance (fn [x y z]
;; ...) :bounds [hx hy hz]}. The scene worker finds the fn's form in the parsed file
;; (by the line Lua says the closure was defined on), translates it to GLSL and Lua
;; (src/sdf/translate.fnl), measures its Lipschitz factor and sends the texts back as
;; plain data; lowering (src/sdf/lower.fnl) turns that data into a descriptor like a
;; primitive's, so every emitter, the CPU reference and the probe take it as they
;; take a sphere.

(local fennel (require :fennel))
(local translate (require :src.sdf.translate))

(local limits
  {;; The Lipschitz estimate: central differences at the centres of a 16^3 grid over
   ;; the bounds grown by half (the far field outside is the box's, 1-Lipschitz),
   ;; and as many random points again, from a fixed seed: 57,344 calls.
   :grid 16 :random 4096 :grow 1.5
   ;; A costly function gets fewer points, so that no estimate takes more than
   ;; about this many operations (0.1 to 0.3 s here); never fewer than an 8^3 grid.
   :measure-ops 3e7 :min-grid 8
   ;; A measured factor at most this is taken as 1: central differences across a
   ;; kink of an exact distance read below 1, and rounding adds ~1e-6.
   :exact-slack 1.01
   ;; A measured factor above that is raised by this margin: the sampled maximum is
   ;; a lower bound of the true one, which may lie between two samples.
   :margin 1.1
   ;; A declared :lipschitz may be below the measured one by this much (rounding of
   ;; the differences), no more.
   :declared-slack 1.01})

;;; Finding the form of a closure

(fn index-fn-forms [node index depth]
  ;; Every (fn ...) list within `node`, by line.
  (when (and (= (type node) :table) (< depth 200) (not (fennel.sym? node)))
    (when (and (fennel.list? node) (fennel.sym? (. node 1)) (= "fn" (tostring (. node 1))))
      (let [src (fennel.ast-source node)]
        (when (and src src.line)
          (when (not (. index src.line)) (tset index src.line []))
          (table.insert (. index src.line) node))))
    (each [k v (pairs node)]
      (index-fn-forms k index (+ depth 1))
      (index-fn-forms v index (+ depth 1))))
  index)

;; A file's fn forms by line, built once per load (a scene of many custom nodes
;; walks its forms once).
(local indexes (setmetatable {} {:__mode :k}))

(fn fn-forms-at [forms line]
  (when (not (. indexes forms)) (tset indexes forms (index-fn-forms forms {} 0)))
  (or (. indexes forms line) []))

(fn param-count [form]
  (let [params (. form (if (fennel.sym? (. form 2)) 3 2))]
    (if (fennel.sequence? params) (length params) -1)))

(fn inside? [inner outer]
  (var found? false)
  (fn walk [node depth]
    (when (and (not found?) (= (type node) :table) (< depth 200))
      (if (rawequal node inner) (set found? true)
          (each [_ v (pairs node)] (walk v (+ depth 1))))))
  (each [i v (ipairs outer)] (when (> i 1) (walk v 1)))
  found?)

(fn find-form [f forms file]
  "The parsed (fn ...) form among `forms` (a file's top-level forms) that closure `f`
was compiled from; or nil, why, and the reason's kind (:elsewhere, :no-form or
:shared-line)."
  (let [info (debug.getinfo f :Su)]
    (if (not= info.source (.. "@" file))
        (values nil "must be written in the scene file itself as (fn [x y z] ...)" :elsewhere)
        (let [found (fn-forms-at forms info.linedefined)
              same-arity (icollect [_ form (ipairs found)]
                           (when (or (= nil info.nparams) (= info.nparams (param-count form))) form))
              outermost (icollect [_ a (ipairs same-arity)]
                          (when (not (accumulate [in? false _ b (ipairs same-arity)]
                                       (or in? (and (not (rawequal a b)) (inside? a b)))))
                            a))
              ;; The same form may be reached twice (a key and a value): one each.
              unique (let [seen {}]
                       (icollect [_ form (ipairs outermost)]
                         (when (not (. seen form)) (tset seen form true) form)))]
          (case (length unique)
            1 (. unique 1)
            0 (values nil "must be written (fn [x y z] ...) in the scene file (a #(...) has no form to translate)" :no-form)
            _ (values nil (.. "line " info.linedefined " holds several functions with "
                              (or info.nparams "as many") " parameters; put the distance function on a line of its own")
                      :shared-line))))))

;; Why a function of the file the distance function calls cannot be translated, by
;; find-form's kind of reason (its own words speak of the distance function).
(fn unreadable [kind name]
  (case kind
    :elsewhere "it is not written in the scene file"
    :no-form (.. "it has no (fn ...) form in the scene file (a #(...) has none); write it (fn "
                 name " [a b] ...)")
    _ "its line holds another function with as many parameters; put it on a line of its own"))

(fn lua-name [name]
  "The Lua name Fennel gives a local named `name` (fennel.mangle is a global's
name): a Lua keyword or a leading digit gets _ before it; - becomes _, any other
character not a letter, digit or _ becomes _XX, its hex code: sd-box is sd_box. A
local that would reuse a name in scope gets a number after it (a second (local r
...) is r0)."
  (let [raw (if (or (name:match "^%d")
                    (. {:and true :break true :do true :else true :elseif true :end true
                        :false true :for true :function true :goto true :if true :in true
                        :local true :nil true :not true :or true :repeat true :return true
                        :then true :true true :until true :while true}
                       name))
                (.. "_" name)
                name)
        (mangled) (: (raw:gsub "-" "_") :gsub "[^%w_]" #(string.format "_%02x" ($:byte)))]
    mangled))

(fn upvalue-of [f name]
  "The value of `f`'s upvalue for the scene's name `name` (found? and the value): the
one named as Fennel mangles `name`, else the only one named so with a number after
it (Fennel's name for a local that shadows another of the same name)."
  (let [base (lua-name name)
        exact []
        numbered []]
    (var i 1)
    (while (debug.getupvalue f i)
      (let [(upname value) (debug.getupvalue f i)]
        (if (= upname base) (table.insert exact [value])
            (and (= (upname:sub 1 (length base)) base) (: (upname:sub (+ 1 (length base))) :match "^%d+$"))
            (table.insert numbered [value])))
      (set i (+ i 1)))
    (if (= 1 (length exact)) (values true (. exact 1 1))
        (and (= 0 (length exact)) (= 1 (length numbered))) (values true (. numbered 1 1))
        false)))

(fn resolver [f forms file]
  "A resolver for translate: names the closure `f` reaches outside itself (its
upvalues), as numbers, math functions and functions of the file (`forms`, `file`)."
  (let [math-names (collect [k v (pairs math)] (when (= (type v) :function) (values v k)))]
    ;; LuaJIT's math.mod is an alias of fmod: call the function by its own name.
    (when math.fmod (tset math-names math.fmod :fmod))
    (fn [name]
      (let [(found? value) (upvalue-of f name)]
        (when found?
          (case (type value)
            :number {:number value}
            :nil {:nil true}
            ;; The name as written when it is math's own (local {: mod} math).
            :function (if (and (= (. math name) value) (. math-names value)) {:math name}
                          (. math-names value) {:math (. math-names value)}
                          (case (find-form value forms file)
                            form {:helper form :resolve (resolver value forms file)}
                            (_ _ kind) {:unreadable (unreadable kind name)}))
            t {:other (.. "a " t)}))))))

;;; Hashing, for the shader's structure key

(fn digest [text]
  "A short hex digest of `text` (two polynomial hashes modulo a prime below 2^32,
exact in doubles) and its length: equal texts, equal digests."
  (let [p 4294967291]
    (var a 0)
    (var b 7)
    (for [i 1 (length text)]
            ;; An array of numbers or vectors (translate checks its items).
            :table {:table value}
      (let [c (text:byte i)]
        (set a (% (+ (* a 31) c) p))
        (set b (% (+ (* b 131) c) p))))
    (string.format "%08x%08x-%d" a b (length text))))

;;; The Lipschitz factor

(fn lcg [seed]
  (var s seed)
  (fn []
    (set s (% (+ (* s 1103515245) 12345) 2147483648))
    (/ s 2147483648)))

(fn measure [cpu bounds args ?cost]
  "The largest gradient length of `cpu` (fn [x y z ...args]) found by central
differences over `bounds` (half extents) grown by limits.grow, and the point; or
nil, a message and the point where it is not finite. `?cost`: operations per call,
to take fewer points for a costly function (see limits.measure-ops)."
  (let [[hx hy hz] (icollect [_ b (ipairs bounds)] (* b limits.grow))
        h (* 1e-4 (math.max hx hy hz))
        unpack (or table.unpack _G.unpack)
        d (fn [x y z] (cpu x y z (unpack args)))
        full (+ (^ limits.grid 3) limits.random)
        points (math.min full (/ limits.measure-ops (* 7 (math.max 1 (or ?cost 1)))))
        n (math.max limits.min-grid
                    (math.min limits.grid (math.floor (^ (* 0.5 points) (/ 1 3)))))
        random (math.floor (* limits.random (/ (^ n 3) (^ limits.grid 3))))
        rand (lcg 12345)]
    (var worst 0)
    (var at [0 0 0])
    (var bad nil)
    (fn sample [x y z]
      (when (not bad)
        (let [v (d x y z)
              gx (/ (- (d (+ x h) y z) (d (- x h) y z)) (* 2 h))
              gy (/ (- (d x (+ y h) z) (d x (- y h) z)) (* 2 h))
              gz (/ (- (d x y (+ z h)) (d x y (- z h))) (* 2 h))
              g (math.sqrt (+ (* gx gx) (* gy gy) (* gz gz)))]
          (if (not (and (= v v) (= g g) (< (math.abs v) math.huge) (< g math.huge)))
              (set bad [x y z])
              (> g worst) (do (set worst g) (set at [x y z]))))))
    (for [i 0 (- n 1)]
      (for [j 0 (- n 1)]
        (for [k 0 (- n 1)]
          (sample (* hx (- (/ (* 2 (+ i 0.5)) n) 1))
                  (* hy (- (/ (* 2 (+ j 0.5)) n) 1))
                  (* hz (- (/ (* 2 (+ k 0.5)) n) 1))))))
    (for [_ 1 random]
      (sample (* hx (- (* 2 (rand)) 1)) (* hy (- (* 2 (rand)) 1)) (* hz (- (* 2 (rand)) 1))))
    (if bad (values nil "gives a value that is not a finite number" bad)
        (values worst at))))

(fn point-text [p]
  (string.format "[%.3g %.3g %.3g]" (. p 1) (. p 2) (. p 3)))

(fn factor [measured ?declared at]
  "The factor the distance is divided by, from the `measured` gradient and the
`?declared` :lipschitz; or nil and why the declaration is refused."
  (if ?declared
      (if (> measured (* ?declared limits.declared-slack))
          (values nil (string.format "declares %g, but the distance changes by %.3g per unit at %s (sampled over its bounds); declare at least %.3g, or leave :lipschitz out to have it measured"
                                     ?declared measured (point-text at) measured))
          ?declared)
      (<= measured limits.exact-slack) 1
      (* measured limits.margin)))

;;; The worker's side: from a closure to plain data

(fn capture [f forms file]
  "Translate the distance closure `f` of scene `file` (whose parsed top-level forms
are `forms`): {:glsl :lua :glsl-name :params :cost}, or nil, a message and a line."
  (case (find-form f forms file)
    (nil msg) (values nil msg (. (debug.getinfo f :S) :linedefined))
    form (translate.translate form {:resolve (resolver f forms file)})))

;;; The main process's check of the texts: they come from the worker, which runs the
;;; scene's code. What the translator writes is a small language; anything else (a
;;; string, a table, a global, a loop past the translator's limits, a recursive call)
;;; is refused before `load` or the shader compiler sees it.

(local lua-words
  (collect [_ w (ipairs ["local" "function" "return" "end" "if" "then" "else" "for" "do" "and"
                         "or" "not" "math" "break"])]
    w true))
(local lua-math
  (collect [_ w (ipairs ["sqrt" "abs" "floor" "ceil" "sin" "cos" "tan" "asin" "acos" "atan"
                         "atan2" "exp" "log" "min" "max"])]
    w true))
(local glsl-words
  (collect [_ w (ipairs ["float" "vec2" "vec3" "vec4" "int" "bool" "return" "if" "else" "for" "break"
                         "p" "sqrt" "abs" "floor" "ceil" "sin" "cos" "tan" "asin" "acos" "atan"
                         "exp" "log" "pow" "min" "max" "mod" "length" "sign"])]
    w true))
(local swizzles {:x true :y true :z true :w true})

(fn tokens [text]
  "The tokens of `text` (names, numbers, operators), or nil at a character the
translator never writes."
  (let [out []
        n (length text)]
    (var i 1)
    (var bad? false)
    (while (and (<= i n) (not bad?))
      (let [ws (text:match "^%s+" i)]
        (if ws (set i (+ i (length ws)))
            (let [tok (or (text:match "^[%a_][%w_]*" i)
                          (text:match "^%d+%.?%d*[eE][-+]?%d+" i)
                          (text:match "^%d+%.?%d*" i)
                          (text:match "^[=~<>!]=" i)
                          (text:match "^&&" i) (text:match "^||" i) (text:match "^%+%+" i)
                          (text:match "^%+=" i)
                          (text:match "^[-+*/%%^(),=<>.;{}?:!]" i))]
              (if tok (do (table.insert out tok) (set i (+ i (length tok))))
                  (set bad? true))))))
    (when (not bad?) out)))

(fn number? [tok] (not= nil (tok:match "^%d")))

(fn signed [toks k]
  ;; The whole number at token k ("-" then digits, or digits) and the index after it.
  (if (= (. toks k) "-")
      (values (and (. toks (+ k 1)) (tonumber (. toks (+ k 1))) (- (tonumber (. toks (+ k 1)))))
              (+ k 2))
      (values (and (. toks k) (tonumber (. toks k))) (+ k 1))))

(fn loop-turns [start stop step]
  (let [a (tonumber start) b (tonumber stop) c (tonumber step)]
    (when (and a b c (not= c 0))
      (math.max 0 (+ 1 (math.floor (/ (- b a) c)))))))

(fn check-lua [text]
  "True when `text` is Lua of the translator's kind: generated names, math's
functions, for loops of constant bounds within translate's limits, calls of helpers
defined before (no recursion).
No value is ever a function but where it is called: a helper's name is defined once
and otherwise only called, math's functions only called, and a variable never
called. So the helpers' calls go from each to ones defined before it, and with every
loop bounded, the text ends: a helper redefined under its own name (which its body
would then call), or one passed to itself as a value, is refused."
  (case (tokens text)
    nil false
    toks
    (let [stack []          ; open blocks: {:kind :turns :name}
          defined {}        ; helpers whose definition has begun
          closed {}         ; helpers whose definition has ended
          max-turns translate.limits.cost]
      (var ok? true)
      (var i 1)
      (fn at [k] (or (. toks (+ i k)) ""))
      (fn work []
        (accumulate [w 1 _ b (ipairs stack)] (* w (or b.turns 1))))
      (while (and ok? (<= i (length toks)))
        (let [t (. toks i)]
          (if (= t "math")
              (do (set ok? (and (= (at 1) ".") (. lua-math (at 2)) (= (at 3) "(") true))
                  (set i (+ i 3)))
              (= t ".") (set ok? false)
              (= t "function")
              (do (table.insert stack {:kind :function :name (when (= (. toks (- i 1)) "local") (at 1))})
                  (set i (+ i 1)))
              (= t "if") (do (table.insert stack {:kind :if}) (set i (+ i 1)))
              (= t "for")
              ;; for vN = A, B[, C] do: whole numbers, maybe negative ("-" then digits).
              (let [(a after-a) (signed toks (+ i 3))
                    (b after-b) (signed toks (+ after-a 1))
                    three? (= (. toks after-b) ",")
                    (c after-c) (if three? (signed toks (+ after-b 1)) (values 1 after-b))
                    turns (and (: (at 1) :match "^v%d+$") (= (at 2) "=") (= (. toks after-a) ",")
                               (loop-turns a b c))]
                (if (and turns (<= turns translate.limits.loop-turns) (= (. toks after-c) "do"))
                    (do (table.insert stack {:kind :for : turns})
                        (set ok? (<= (work) max-turns))
                        (set i (+ after-c 1)))
                    (set ok? false)))
              (= t "end")
              (let [b (table.remove stack)]
                (when (and b b.name) (tset closed b.name true))
                (set ok? (not= nil b))
                (set i (+ i 1)))
              (= t "do") (set ok? false)
              (t:match "^v%d+$")
              ;; A variable holds a number: never called.
              (do (set ok? (not= (at 1) "("))
                  (set i (+ i 1)))
              (or (. lua-words t) (number? t) (not (t:match "^[%a_]")))
              (set i (+ i 1))
              (t:match "^sdCustom%d*Fn%d+$")
              ;; A helper's name: its one definition, or a call of one defined before.
              (do (set ok? (if (= (. toks (- i 1)) "function")
                               (when (not (. defined t)) (tset defined t true) true)
                               (and (. closed t) (= (at 1) "(") true)))
                  (set i (+ i 1)))
              (set ok? false))))
      (and ok? (= 0 (length stack))))))

(fn check-glsl [text name]
  "True when `text` is GLSL of the translator's kind for the function `name`."
  (case (tokens text)
    nil false
    toks
    (let [braces []]
      (var ok? true)
      (var pending nil)   ; a for header's turns, until its {
      (var i 1)
      (fn at [k] (or (. toks (+ i k)) ""))
      (while (and ok? (<= i (length toks)))
        (let [t (. toks i)]
          (if (= t "for")
              ;; for ( int iN = A ; iN <= B ; iN ++ | iN += C ) {
              (let [(a after-a) (signed toks (+ i 5))
                    cmp (. toks (+ after-a 2))
                    (b after-b) (signed toks (+ after-a 3))
                    update (. toks (+ after-b 2))
                    (c) (if (= update "++") (values 1) (signed toks (+ after-b 3)))
                    turns (and (= (at 1) "(") (= (at 2) "int") (: (at 3) :match "^i%d+$")
                               (= (at 4) "=") (= (. toks after-a) ";")
                               (or (= cmp "<=") (= cmp ">=")) (= (. toks after-b) ";")
                               (or (= update "++") (= update "+="))
                               (loop-turns a b c))]
                (set ok? (and turns (<= turns translate.limits.loop-turns) true))
                (set pending turns)
                (set i (+ i 2)))
              (= t "{") (do (table.insert braces (or pending 1)) (set pending nil) (set i (+ i 1))
                            (set ok? (<= (accumulate [w 1 _ b (ipairs braces)] (* w b))
                                         translate.limits.cost)))
              (= t "}") (do (set ok? (not= nil (table.remove braces))) (set i (+ i 1)))
              (= t ".") (do (set ok? (and (. swizzles (at 1))
                                           (or (= (. toks (- i 1)) "p") (: (. toks (- i 1)) :match "^[va]%d+$"))
                                           true))
                            (set i (+ i 2)))
              (or (. glsl-words t) (number? t) (t:match "^[via]%d+$") (= t name)
                  (and (= (t:sub 1 (length name)) name) (: (t:sub (+ 1 (length name))) :match "^Fn%d+$"))
                  (not (t:match "^[%a_]")))
              (set i (+ i 1))
              (set ok? false))))
      (and ok? (= 0 (length braces))))))

(fn check-data [c]
  "Nil when the custom node data `c` (from the worker) is as the translator writes it,
else why not."
  (if (not (and (= (type c) :table) (= (type c.glsl) :string) (= (type c.lua) :string)
                (= (type c.glsl-name) :string) (c.glsl-name:match "^sdCustom%d+$")
                (= (type c.key) :string) (= (type c.params) :table)))
      "its data is not a translation"
      (not (check-glsl c.glsl c.glsl-name)) "its GLSL is not the translator's"
      (not (check-lua c.lua)) "its Lua is not the translator's"
      (not= c.key (digest c.glsl)) "its digest does not match its GLSL"))

;;; The lowering's side: a descriptor from the data

(local cache {})
(var cached 0)

(fn descriptor [node]
  "The primitive-like descriptor (see src/sdf/primitives.fnl) of custom node `node`
(validated data: :custom {:glsl :lua :glsl-name :key :params}, :params, :bounds,
:lipschitz), or nil for any other node. Its function takes the parameters in the
order of the fn's arguments, then 1 / :lipschitz, by which it multiplies. The
descriptors of nodes with the same texts share their GLSL and their Lua function."
  (when (= node.kind :custom)
    (let [c node.custom
          ;; The texts themselves key the cache: checked once, then found again at
          ;; every lowering (each value edit lowers the scene again).
          ;; The parameters' names too: two functions that differ only in them have
          ;; the same texts, and each packs its own :params.
          text-key (and (= (type c) :table) (= (type c.glsl) :string) (= (type c.lua) :string)
                        (= (type c.glsl-name) :string) (= (type c.key) :string)
                        (= (type c.params) :table)
                        (accumulate [ok? true _ n (ipairs c.params)] (and ok? (= (type n) :string)))
                        (.. c.glsl-name "\n" c.key "\n" c.glsl "\n" c.lua "\n" (table.concat c.params " ")))
          bad (if (not text-key) "its data is not a translation"
                  (not (. cache text-key)) (check-data c))
          _ (when bad
              (let [reason (.. "a custom node: " bad " (refused)")]
                (error {:lower-error (.. (tostring node.path) ": " reason) : reason : node})))
          key text-key]
      (when (not (. cache key))
        (when (> cached 256)
          (each [k (pairs cache)] (tset cache k nil))
          (set cached 0))
        (set cached (+ cached 1))
        (let [names c.params
              args (icollect [i _ (ipairs names)] {:name (.. "a" i) :type :float})]
          (table.insert args {:name :scale :type :float})
          (tset cache key
                {:kind (.. "custom:" c.glsl-name ":" c.key)
                 :doc "A distance function written in the scene."
                 :params []
                 :class :bound
                 :lipschitz 1
                 : args
                 :arg-size (length args)
                 :pack (fn [o]
                         (let [out (icollect [_ n (ipairs names)] (. o.params n))]
                           (table.insert out (/ 1 o.lipschitz))
                           out))
                 :glsl-name c.glsl-name
                 :glsl c.glsl
                 :cpu (translate.compile-lua c.lua)
                 :bounds (fn [o] o.bounds)})))
      ;; The node's own factor, for --tree: the function divides by it already, and
      ;; nothing reads a primitive's factor to divide again.
      (doto (collect [k v (pairs (. cache key))] k v)
        (tset :lipschitz (or node.lipschitz 1))))))

{: capture : check-data : measure : factor : digest : descriptor : find-form : check-lua : check-glsl
 : limits}
  ;; break: an early end of a for loop (&until, a stop of (math.min n K)), which
  ;; only shortens a bounded loop.

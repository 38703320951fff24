;; A translator from a numeric subset of Fennel to GLSL and Lua: a scene's distance
;; function, given as its parsed form (the Fennel parser's AST), becomes one GLSL
;; function for the shader and one Lua function for the CPU reference, both from the
;; one walk over the form, so the two cannot say different things.
;;
;; The subset (what a distance needs, and what both languages mean the same way):
;;   numbers; the function's arguments; let (names and (a b c) for several values),
;;   local, var and set (of a var of the same function; (a b) for several values); if (any number of branches,
;;   with an else; (if (> x 0) 1 (< x 0) -1 0) of a name x is GLSL's sign(x)), when,
;;   do, -> and ->>; values (at most 4); helper functions (fn in a let or a
;;   body, not recursive, using only their own arguments, numbers and other helpers);
;;   numeric for with constant whole-number bounds (at most 64 turns); + - * / %
;;   (floored, GLSL's mod) and ^ with a whole constant exponent from 0 to 8;
;;   < > <= >= = not= and and, or, not over comparisons; math.sqrt abs floor ceil sin
;;   cos tan asin acos atan (1 or 2 arguments: atan(y, x)) exp log pow min max;
;;   GLSL's clamp mix fract sign step smoothstep round mod as math.clamp ... (see
;;   `library`); math.pi and math.huge (1e30 in both texts). A name from outside the
;;   function is looked up by `?resolve`: a number (inlined), a math function (as
;;   math.x), nil under a name of `library` ((local {: clamp} math)) or a function of
;;   the file (a helper).
;; Anything else is refused with the line and the construct. The output holds only
;; generated names (p, v0 v1 ..., i0 ... for loop counters, a0 ... for vector
;; arguments, sdCustom and its helpers sdCustomFn0 ...) and floats with a decimal
;; point (a loop counter's bounds are ints): nothing of the scene's text, and the
;; same text for the same form.

(local fennel (require :fennel))
(local text (require :src.util.text))

(local limits
  {:loop-turns 64     ; one for loop's turns: a constant bound, unrolled or not
   :cost 4000         ; operations per evaluation, loops counted by their turns
                      ; (scenes/custom.fnl: the gyroid shell cut by a sphere 25,
                      ; the six blended spheres' loop 150)
   :locals 150        ; names in one function (Lua allows 200 live locals)
   :values 4          ; values a helper returns: GLSL's vec4 at most
   :helpers 32
   :power 8})         ; the largest constant exponent of ^

(local supported
  "numbers, let, local, var/set, if, when, do, -> ->>, values, fn helpers, for with constant bounds, + - * / % ^, comparisons, and/or/not, math functions")

;; math's functions: the GLSL name and the argument counts taken (none: one or more).
(local math-functions
  {:sqrt {:glsl "sqrt" :counts {1 true}}
   :abs {:glsl "abs" :counts {1 true}}
   :floor {:glsl "floor" :counts {1 true}}
   :ceil {:glsl "ceil" :counts {1 true}}
   :sin {:glsl "sin" :counts {1 true}}
   :cos {:glsl "cos" :counts {1 true}}
   :tan {:glsl "tan" :counts {1 true}}
   :asin {:glsl "asin" :counts {1 true}}
   :acos {:glsl "acos" :counts {1 true}}
   :atan {:glsl "atan" :counts {1 true 2 true}}
   :exp {:glsl "exp" :counts {1 true}}
   :log {:glsl "log" :counts {1 true}}
   :pow {:glsl "pow" :counts {2 true}}
   :min {:glsl "min"}
   :max {:glsl "max"}})

;; GLSL's own functions that Lua's math lacks, called as math.NAME (or a name
;; destructured from math: (local {: clamp} math), which holds nil when the file
;; runs, as the distance function is never called there). Each is written out the
;; same way in both languages (see library-call), so the CPU and the GPU agree where
;; GLSL leaves the builtin loose: round is floor(x + 0.5) (GLSL's round may go either
;; way at .5), clamp is min(max(x, lo), hi) (GLSL's is undefined for lo > hi), mod
;; is % (GLSL's mod, floored; not Lua 5.1's math.mod, an alias of fmod). :args names
;; the arguments for messages; :eval folds constant arguments.
(local library
  {:clamp {:args "x lo hi" :eval #(math.min (math.max $1 $2) $3)}
   :mix {:args "a b t" :eval #(+ (* $1 (- 1 $3)) (* $2 $3))}
   :fract {:args "x" :eval #(- $1 (math.floor $1))}
   :sign {:args "x" :eval #(if (> $1 0) 1 (< $1 0) -1 0)}
   :step {:args "edge x" :eval #(if (< $2 $1) 0 1)}
   :smoothstep {:args "edge0 edge1 x"
                :eval #(let [t (math.min (math.max (/ (- $3 $1) (- $2 $1)) 0) 1)]
                         (* t t (- 3 (* 2 t))))}
   :round {:args "x" :eval #(math.floor (+ $1 0.5))}
   :mod {:args "x y" :eval #(- $1 (* $2 (math.floor (/ $1 $2))))}})

(each [name spec (pairs library)]
  (let [(_ spaces) (spec.args:gsub " " "")]
    (tset math-functions name {:library true :counts {(+ spaces 1) true} :args spec.args})))

;; GLSL has no portable infinity (1.0 / 0.0 is undefined): math.huge is this large
;; number in both texts. Far beyond any scene and any draw distance, and its square
;; is still a float32 (1e60 is not: 1e30 leaves room for arithmetic).
(local huge 1e30)

(local math-constants {:pi math.pi :huge huge})

(local math-names
  ["sqrt" "abs" "floor" "ceil" "sin" "cos" "tan" "asin" "acos" "atan" "exp" "log" "pow" "min"
   "max" "clamp" "mix" "fract" "sign" "step" "smoothstep" "round" "mod"])

(local math-call-list
  "math.sqrt abs floor ceil sin cos tan asin acos atan exp log pow min max and GLSL's clamp mix fract sign step smoothstep round mod as math.clamp ...")

(local math-list
  "math.sqrt abs floor ceil sin cos tan asin acos atan exp log pow min max, GLSL's clamp mix fract sign step smoothstep round mod, and math.pi huge")

;; Names authors reach for that go by another name here: the hint to give instead of
;; a guess at the spelling.
(local aliases
  {:fmod "for a remainder write (% a b) or (math.mod a b), floored as GLSL's mod (math.fmod truncates toward zero)"
   :lerp "GLSL's mix is (math.mix a b t)"
   :frac "GLSL's fract is (math.fract x)"
   :saturate "write (math.clamp x 0 1)"
   :atan2 "write (math.atan y x), GLSL's atan(y, x)"
   :sgn "write (math.sign x)"
   :length "write (math.sqrt (+ (* x x) (* y y) (* z z))), which becomes GLSL's length()"
   :trunc "write (if (< x 0) (math.ceil x) (math.floor x))"
   :modf "write (math.fract x) and (math.floor x)"
   :huge "math.huge is a value, not a function"
   :pi "math.pi is a value, not a function"})

;; Forms a reader may expect to work, with a hint at what to write instead.
(local refused-forms
  {:while "use for with constant bounds"
   :each "no tables"
   :lambda "use fn"
   :λ "use fn"
   :hashfn "use fn"
   :tset "no tables"
   :. "no tables"
   :length "no tables"
   :# "no tables"
   :.. "no strings"
   :// "use math.floor of /"})

;;; Failing

(fn line-of [node]
  (let [src (and (= (type node) :table) (fennel.ast-source node))]
    (and src src.line)))

(fn refuse [st node what]
  "Stop the translation with `what`, at `node`'s line (or the innermost form's)."
  (error {:translate-error what :line (or (line-of node) st.line)} 0))

(fn not-supported [st node what ?hint]
  (refuse st node (.. what " is not supported in a distance function ("
                      (if ?hint (.. ?hint "; ") "") "supported: " supported ")")))

;;; Suggestions, for a name the function may not use

(fn closest [name candidates]
  "The candidate nearest `name` when it is near enough to be a slip of the pen (at
most 2 edits, and fewer than half its letters), else nil; the first of a tie."
  (var best nil)
  (var best-d math.huge)
  (each [_ c (ipairs candidates)]
    (let [d (text.edit-distance name c)]
      (when (and (< d best-d) (<= d 2) (< d (/ (length name) 2)))
        (set best c)
        (set best-d d))))
  best)

(fn suggestion [name ?helpers]
  "A hint for `name` (math.x or x) that is no function here: its alias's hint, or
'did you mean ...?' among math's functions and `?helpers` (names), or \"\"."
  (let [short (or (name:match "^math%.(.+)$") name)
        math-guess (closest short math-names)
        helper-guess (and ?helpers (closest name ?helpers))]
    (if (. aliases short) (.. "; " (. aliases short))
        (and helper-guess (or (not math-guess) (<= (text.edit-distance name helper-guess)
                                                   (text.edit-distance short math-guess))))
        (.. "; did you mean `" helper-guess "`?")
        math-guess (.. "; did you mean math." math-guess "?")
        "")))

;;; Numbers and names

(fn glsl-number [n]
  ;; Nine significant digits give back the float32; always a decimal point.
  (let [s (string.format "%.9g" (math.abs n))
        s (if (s:find "%.") s
              (s:find "e") (s:gsub "e" ".0e" 1)
              (.. s ".0"))]
    (if (< n 0) (.. "(-" s ")") s)))

(fn lua-number [n]
  ;; The shortest of 15 and 17 digits that gives back the double.
  (let [short (string.format "%.15g" n)
        s (if (= (tonumber short) n) short (string.format "%.17g" n))]
    (if (< n 0) (.. "(" s ")") s)))

(fn constant [st node n]
  (when (or (not= n n) (= n math.huge) (= n (- math.huge)))
    (refuse st node (.. "the number " (tostring n) " is not finite")))
  {:g (glsl-number n) :l (lua-number n) :t :float :const n})

(fn fresh! [st prefix]
  (let [name (.. prefix st.counter)]
    (set st.counter (+ st.counter 1))
    name))

(fn count-local! [st node n]
  (let [f st.fn]
    (set f.locals (+ f.locals (or n 1)))
    (when (> f.locals limits.locals)
      (refuse st node (.. "the function needs more than " limits.locals
                          " local values; split it into helper functions")))))

(fn cost! [st node n]
  (set st.cost (+ st.cost (* st.weight n)))
  (when (> st.cost limits.cost)
    (refuse st node (.. "the function takes more than " limits.cost
                        " operations per point (loops count each turn); the shader would crawl"))))

;;; Output: blocks of paired lines, flattened once at the end

(fn emit! [st g l]
  "Append a GLSL line `g` and a Lua line `l` (either may be nil) to the current block."
  (table.insert st.out {: g : l}))

(fn capture [st f]
  "Call `f` with output going to a new block; returns the block and f's value."
  (let [saved st.out
        block []]
    (set st.out block)
    (let [value (f)]
      (set st.out saved)
      (values block value))))

(fn nest! [st g-open l-open block g-close l-close]
  (table.insert st.out {:g g-open :l l-open : block :g-close g-close :l-close l-close}))

(fn flatten [block which indent lines]
  (each [_ item (ipairs block)]
    (let [line (. item which)
          pad (string.rep "    " indent)]
      (when line (table.insert lines (.. pad line)))
      (when item.block
        (flatten item.block which (+ indent 1) lines)
        (let [close (. item (.. which "-close"))]
          (when close (table.insert lines (.. pad close)))))))
  lines)

;;; Scopes: name -> binding, each binding owned by one function

(fn new-scope [parent] {:names {} : parent})

(fn bind! [sc name binding] (tset sc.names name binding))

(fn lookup [sc name]
  (var found nil)
  (var s sc)
  (while (and s (= found nil))
    (set found (. s.names name))
    (set s s.parent))
  found)

(fn sym-name [node] (and (fennel.sym? node) (tostring node)))

(fn check-name! [st node]
  (let [name (sym-name node)]
    (when (or (not name) (name:find "[%.:]") (= name "&") (= name "nil"))
      (refuse st node (.. "expected a name here, got " (if name (.. "`" name "`")
                                                           (fennel.sequence? node) "a [...] table pattern"
                                                           (fennel.table? node) "a {...} table pattern"
                                                           (tostring node)))))
    name))

;;; Expressions: each gives a list of parts {:g GLSL :l Lua :t :float|:bool :const n}

(var expr nil)
(var body nil)

(fn one [st node parts ?what]
  (when (not= 1 (length parts))
    (refuse st node (.. (or ?what "this expression") " gives " (length parts)
                        " values where one is needed")))
  (. parts 1))

(fn number-arg [st node]
  (let [p (one st node (expr st node))]
    (when (not= p.t :float)
      (refuse st node "a comparison is used as a number (and/or/not and if conditions take comparisons; arithmetic takes numbers)"))
    p))

(fn bool-arg [st node]
  (let [p (one st node (expr st node) "a condition")]
    (when (not= p.t :bool)
      (refuse st node "a condition must be a comparison like (< a b), or and/or/not of comparisons: a number is always true in Fennel and never in GLSL"))
    p))

(fn args-of [node] (fcollect [i 2 (length node)] (. node i)))

(fn fold [st node parts op g-op l-op identity]
  (if (= 0 (length parts)) (constant st node identity)
      (accumulate [acc nil _ p (ipairs parts)]
        (if (= acc nil) p
            (and acc.const p.const) (constant st node (op acc.const p.const))
            {:g (.. "(" acc.g " " g-op " " p.g ")") :l (.. "(" acc.l " " l-op " " p.l ")")
             :t :float}))))

(fn arithmetic [st node op]
  (let [args (icollect [_ a (ipairs (args-of node))] (number-arg st a))]
    (cost! st node (math.max 1 (- (length args) 1)))
    (case op
      "+" [(fold st node args #(+ $1 $2) "+" "+" 0)]
      "*" [(fold st node args #(* $1 $2) "*" "*" 1)]
      "-" (if (= 0 (length args)) (refuse st node "(-) needs an argument")
              (= 1 (length args))
              (let [a (. args 1)]
                [(if a.const (constant st node (- a.const))
                     {:g (.. "(-" a.g ")") :l (.. "(-" a.l ")") :t :float})])
              [(fold st node args #(- $1 $2) "-" "-" 0)])
      "/" (if (= 0 (length args)) (refuse st node "(/) needs an argument")
              (= 1 (length args)) [(fold st node [(constant st node 1) (. args 1)] #(/ $1 $2) "/" "/" 1)]
              [(fold st node args #(/ $1 $2) "/" "/" 1)])
      "%" (if (not= 2 (length args)) (refuse st node "(% a b) takes two arguments")
              (let [[a b] args]
                [{:g (.. "mod(" a.g ", " b.g ")") :l (.. "(" a.l " % " b.l ")") :t :float}])))))

(fn declare! [st node part]
  "A new local holding `part`'s value; its name as a part."
  (let [name (fresh! st "v")]
    (count-local! st node)
    (emit! st (.. (if (= part.t :bool) "bool " "float ") name " = " part.g ";")
           (.. "local " name " = " part.l))
    {:g name :l name :t part.t}))

(fn power [st node]
  (let [args (args-of node)]
    (when (not= 2 (length args)) (refuse st node "(^ a n) takes two arguments"))
    (let [base (number-arg st (. args 1))
          n (. (number-arg st (. args 2)) :const)]
      (when (not (and n (= n (math.floor n)) (<= 0 n limits.power)))
        (refuse st node (.. "(^ a n) needs a whole constant n from 0 to " limits.power
                            "; for other powers use (math.pow a b), with a >= 0")))
      (cost! st node (math.max 1 (- n 1)))
      (if (= n 0) [(constant st node 1)]
          base.const [(constant st node (^ base.const n))]
          (let [b (if (= n 1) base (declare! st node base))]
            [(fold st node (fcollect [_ 1 n] b) #(* $1 $2) "*" "*" 1)])))))

(local comparison-ops {"<" ["<" "<"] ">" [">" ">"] "<=" ["<=" "<="] ">=" [">=" ">="]
                       "=" ["==" "=="] "not=" ["!=" "~="] "~=" ["!=" "~="]})

(fn comparison [st node op]
  (let [args (icollect [_ a (ipairs (args-of node))] (number-arg st a))
        [g-op l-op] (. comparison-ops op)]
    (when (< (length args) 2) (refuse st node (.. "(" op " ...) needs two or more arguments")))
    (when (and (> (length args) 2) (or (= op "not=") (= op "~=")))
      (refuse st node (.. "(" op " a b) takes two arguments")))
    (cost! st node (- (length args) 1))
    (let [pairs* (fcollect [i 1 (- (length args) 1)]
                   (let [a (. args i) b (. args (+ i 1))]
                     {:g (.. "(" a.g " " g-op " " b.g ")") :l (.. "(" a.l " " l-op " " b.l ")")
                      :t :bool}))]
      [(accumulate [acc nil _ p (ipairs pairs*)]
         (if acc {:g (.. "(" acc.g " && " p.g ")") :l (.. "(" acc.l " and " p.l ")") :t :bool}
             p))])))

(fn logic [st node op]
  (let [args (icollect [_ a (ipairs (args-of node))] (bool-arg st a))]
    (if (= op "not")
        (if (not= 1 (length args)) (refuse st node "(not c) takes one argument")
            (let [a (. args 1)] [{:g (.. "(!" a.g ")") :l (.. "(not " a.l ")") :t :bool}]))
        (if (= 0 (length args)) (refuse st node (.. "(" op ") needs an argument"))
            [(accumulate [acc nil _ p (ipairs args)]
               (if acc {:g (.. "(" acc.g (if (= op "and") " && " " || ") p.g ")")
                        :l (.. "(" acc.l " " op " " p.l ")") :t :bool}
                   p))]))))

(fn squared-names [form]
  ;; The names a, b ... of a form (+ (* a a) (* b b) ...) of two to four terms, else
  ;; nil.
  (when (and (fennel.list? form) (= "+" (sym-name (. form 1))) (<= 3 (length form) 5))
    (let [names (fcollect [i 2 (length form)]
                  (let [term (. form i)]
                    (when (and (fennel.list? term) (= 3 (length term)) (= "*" (sym-name (. term 1)))
                               (sym-name (. term 2)) (= (sym-name (. term 2)) (sym-name (. term 3))))
                      (. term 2))))]
      (when (= (length names) (- (length form) 1)) names))))

(fn repeatable [st node p]
  "`p` itself when its text may be written twice (a constant or a name), else a new
local holding it: an argument a library function reads twice is computed once."
  (if (or p.const (and (p.g:match "^[%w_]+[.xyzw]*$") (p.l:match "^[%w_]+$"))) p
      (declare! st node p)))

(fn sign-part [st node p]
  ;; GLSL's sign(); in Lua the same three cases (a number is never false in Lua).
  (let [x (repeatable st node p)]
    {:g (.. "sign(" x.g ")") :l (.. "(" x.l " > 0 and 1 or (" x.l " < 0 and -1 or 0))")
     :t :float}))

(fn library-call [st node fname args]
  ;; GLSL's functions of `library`, written out alike in both languages; constant
  ;; arguments fold.
  (let [costs {:clamp 2 :mix 3 :fract 1 :sign 2 :step 1 :smoothstep 7 :round 1 :mod 2}
        g1 (glsl-number 1)]
    (cost! st node (. costs fname))
    (if (accumulate [all? true _ a (ipairs args)] (and all? (not= nil a.const)))
        [(constant st node ((. library fname :eval) ((or table.unpack _G.unpack) (icollect [_ a (ipairs args)] a.const))))]
        (case fname
          :clamp (let [[x lo hi] args]
                   [{:g (.. "min(max(" x.g ", " lo.g "), " hi.g ")")
                     :l (.. "math.min(math.max(" x.l ", " lo.l "), " hi.l ")") :t :float}])
          ;; GLSL's definition, a (1 - t) + b t: exactly a at t = 0 and b at t = 1.
          :mix (let [[a b t*] args
                     t (repeatable st node t*)]
                 [{:g (.. "((" a.g " * (" g1 " - " t.g ")) + (" b.g " * " t.g "))")
                   :l (.. "((" a.l " * (1 - " t.l ")) + (" b.l " * " t.l "))") :t :float}])
          :fract (let [x (repeatable st node (. args 1))]
                   [{:g (.. "(" x.g " - floor(" x.g "))") :l (.. "(" x.l " - math.floor(" x.l "))")
                     :t :float}])
          :sign [(sign-part st node (. args 1))]
          ;; 0 below the edge, 1 from it on, as GLSL's step.
          :step (let [[edge x] args]
                  [{:g (.. "((" x.g " < " edge.g ") ? 0.0 : " g1 ")")
                    :l (.. "(" x.l " < " edge.l " and 0 or 1)") :t :float}])
          ;; GLSL's definition: t = clamp((x - e0) / (e1 - e0), 0, 1), t t (3 - 2 t).
          :smoothstep (let [[e0 e1 x] args
                            t (declare! st node
                                        {:g (.. "min(max(((" x.g " - " e0.g ") / (" e1.g " - " e0.g ")), 0.0), " g1 ")")
                                         :l (.. "math.min(math.max(((" x.l " - " e0.l ") / (" e1.l " - " e0.l ")), 0), 1)")
                                         :t :float})]
                        [{:g (.. "((" t.g " * " t.g ") * (3.0 - (2.0 * " t.g ")))")
                          :l (.. "((" t.l " * " t.l ") * (3 - (2 * " t.l ")))") :t :float}])
          :round (let [[x] args]
                   [{:g (.. "floor(" x.g " + 0.5)") :l (.. "math.floor(" x.l " + 0.5)") :t :float}])
          ;; As %: GLSL's mod, and Lua's % (a - floor(a / b) b in both).
          :mod (let [[x y] args]
                 [{:g (.. "mod(" x.g ", " y.g ")") :l (.. "(" x.l " % " y.l ")") :t :float}])))))

(fn math-call [st node fname]
  (let [spec (. math-functions fname)
        args (icollect [_ a (ipairs (args-of node))] (number-arg st a))
        n (length args)]
    (when (if spec.counts (not (. spec.counts n)) (= n 0))
      (refuse st node (.. "math." fname " takes "
                          (if (= fname :atan) "1 or 2 arguments (atan y x)"
                              spec.library (let [(_ k) (spec.args:gsub " " "")]
                                             (.. (+ k 1) " argument" (if (> k 0) "s" "")
                                                 " (math." fname " " spec.args ")"))
                              (not spec.counts) "one or more arguments"
                              (. spec.counts 2) "2 arguments" "1 argument")
                          ", got " n)))
    (when (not spec.library) (cost! st node (math.max 1 (- n 1))))
    (if spec.library (library-call st node fname args)
        (or (= fname :min) (= fname :max))
        [(accumulate [acc nil _ p (ipairs args)]
           (if acc {:g (.. fname "(" acc.g ", " p.g ")") :l (.. "math." fname "(" acc.l ", " p.l ")")
                    :t :float}
               p))]
        (let [gs (table.concat (icollect [_ a (ipairs args)] a.g) ", ")
              ls (table.concat (icollect [_ a (ipairs args)] a.l) ", ")
              ;; The square root of a sum of squares is GLSL's length(), as a
              ;; hand-written distance says it (the same rounding as length(p)).
              lengths (when (= fname :sqrt) (squared-names (. node 2)))]
          [{:g (if lengths
                   (.. "length(vec" (length lengths) "("
                       (table.concat (icollect [_ n (ipairs lengths)] (. (number-arg st n) :g)) ", ")
                       "))")
                   (.. spec.glsl "(" gs ")"))
            :l (if (= fname :pow) (.. "(" (. args 1 :l) " ^ " (. args 2 :l) ")")
                   (.. (if (and (= fname :atan) (= n 2)) "math.atan2" (.. "math." fname)) "(" ls ")"))
            :t :float}]))))

(fn values-form [st node]
  (icollect [_ a (ipairs (args-of node))] (number-arg st a)))

(fn vec-type [n] (if (= n 1) "float" (.. "vec" n)))

(fn helper-call [st node helper]
  (let [args (icollect [_ a (ipairs (args-of node))] (number-arg st a))]
    (when (not= (length args) helper.nargs)
      (refuse st node (.. "a helper function takes " helper.nargs " arguments, given "
                          (length args))))
    (set st.cost (+ st.cost (* st.weight helper.cost)))
    (cost! st node 1)
    (let [gs (.. helper.name "(" (table.concat (icollect [_ a (ipairs args)] a.g) ", ") ")")
          ls (.. helper.name "(" (table.concat (icollect [_ a (ipairs args)] a.l) ", ") ")")]
      (if (= helper.nret 1) [{:g gs :l ls :t :float}]
          ;; Several values: a vector in GLSL, as many locals in Lua.
          (let [v (fresh! st "v")
                names (fcollect [_ 1 helper.nret] (fresh! st "v"))]
            (count-local! st node helper.nret)
            (emit! st (.. (vec-type helper.nret) " " v " = " gs ";")
                   (.. "local " (table.concat names ", ") " = " ls))
            (icollect [i name (ipairs names)]
              {:g (.. v "." (. ["x" "y" "z" "w"] i)) :l name :t :float}))))))

(fn check-parts [st node parts]
  ;; What a value may be: numbers, or one comparison.
  (when (> (length parts) limits.values)
    (refuse st node (.. "gives " (length parts) " values; at most " limits.values)))
  (when (and (> (length parts) 1) (accumulate [b? false _ p (ipairs parts)] (or b? (= p.t :bool))))
    (refuse st node "several values must all be numbers"))
  parts)

(fn sign-operand [node]
  ;; The x of (if (> x 0) 1 (< x 0) -1 0), a name: GLSL's sign(x). Written out as
  ;; two tests and selects, grids of 16 hex prisms or solid angles drew 11-12% slower
  ;; on llvmpipe than with the builtin of their hand-written GLSL; with sign(), 2%.
  (let [[_ c1 a c2 b e] node
        test? (fn [c op]
                (and (fennel.list? c) (= 3 (length c)) (= op (sym-name (. c 1)))
                     (sym-name (. c 2)) (= 0 (. c 3))))]
    (when (and (= 6 (length node)) (= a 1) (= b -1) (= e 0)
               (test? c1 ">") (test? c2 "<") (= (sym-name (. c1 2)) (sym-name (. c2 2))))
      (. c1 2))))

(fn if-chain [st node]
  (let [args (args-of node)
        n (length args)]
    (when (< n 2) (refuse st node "(if c a b) needs a condition and branches"))
    (when (= 0 (% n 2))
      (refuse st node "an if needs an else branch (the last argument): a distance has a value everywhere"))
    ;; Each condition's own lines and the branches' lines, captured apart.
    (let [arms (fcollect [i 1 (- n 1) 2]
                 (let [(cblock c) (capture st #(bool-arg st (. args i)))
                       (bblock b) (capture st #(check-parts st (. args (+ i 1)) (expr st (. args (+ i 1)))))]
                   {: cblock : c : bblock : b}))
          (eblock e) (capture st #(check-parts st (. args n) (expr st (. args n))))
          width (length e)]
      (each [_ arm (ipairs arms)]
        (when (or (not= width (length arm.b))
                  (accumulate [bad? false i p (ipairs arm.b)] (or bad? (not= p.t (. e i :t)))))
          (refuse st node "the branches of an if give different kinds or numbers of values")))
      ;; No value at all: an if for its sets, in a body.
      (cost! st node (length arms))
      (if (and (= width 1) (= 0 (length eblock))
               (accumulate [simple? true _ arm (ipairs arms)]
                 (and simple? (= 0 (length arm.cblock)) (= 0 (length arm.bblock)))))
          ;; Expressions only: the conditional expression (a number is never false in
          ;; Lua, so `c and a or b` is c ? a : b).
          [(accumulate [acc (. e 1) i (ipairs arms)]
             (let [arm (. arms (- (length arms) i -1))
                   b (. arm.b 1)]
               {:g (.. "(" arm.c.g " ? " b.g " : " acc.g ")")
                :l (.. "(" arm.c.l " and " b.l " or " acc.l ")") :t acc.t}))]
          (let [results (icollect [_ p (ipairs e)]
                          (let [name (fresh! st "v")] {:g name :l name :t p.t}))
                assign (fn [parts]
                         (icollect [i p (ipairs parts)]
                           {:g (.. (. results i :g) " = " p.g ";")
                            :l (.. (. results i :l) " = " p.l)}))]
            (count-local! st node width)
            (each [_ r (ipairs results)]
              (emit! st (.. (if (= r.t :bool) "bool " "float ") r.g ";") nil))
            (when (> width 0)
              (emit! st nil (.. "local " (table.concat (icollect [_ r (ipairs results)] r.l) ", "))))
            ;; if (c1) {...} else { c2's lines; if (c2) {...} else {...} }
            (fn chain [k]
              (if (> k (length arms))
                  (let [block eblock]
                    (each [_ line (ipairs (assign e))] (table.insert block line))
                    block)
                  (let [arm (. arms k)
                        out arm.cblock
                        then arm.bblock]
                    (each [_ line (ipairs (assign arm.b))] (table.insert then line))
                    (table.insert out {:g (.. "if (" arm.c.g ") {") :l (.. "if " arm.c.l " then")
                                       :block then})
                    (table.insert out {:g "} else {" :l "else" :block (chain (+ k 1))
                                       :g-close "}" :l-close "end"})
                    out)))
            (each [_ item (ipairs (chain 1))] (table.insert st.out item))
            results)))))

(fn if-form [st node]
  (case (sign-operand node)
    x (let [p (number-arg st x)]
        (cost! st node 2)
        [(sign-part st node p)])
    _ (if-chain st node)))

(fn when-form [st node]
  (let [args (args-of node)]
    (when (< (length args) 1) (refuse st node "(when c ...) needs a condition"))
    (let [(cblock c) (capture st #(bool-arg st (. args 1)))
          (bblock) (capture st #(body st (new-scope st.scope) (fcollect [i 2 (length args)] (. args i)) node))]
      (cost! st node 1)
      (each [_ item (ipairs cblock)] (table.insert st.out item))
      (nest! st (.. "if (" c.g ") {") (.. "if " c.l " then") bblock "}" "end")
      [])))

(fn bind-value! [st node sc name parts]
  "Bind `name` in `sc` to the single value `parts`: a constant stays inline, anything
else gets a local."
  (let [p (one st node parts (.. "the value bound to `" name "`"))]
    (bind! sc name {:kind :value :fn st.fn :part (if p.const p (declare! st node p))})))

(var define-helper nil)

(fn bind-pattern! [st sc pattern value-node]
  (if (and (fennel.list? value-node) (= "fn" (sym-name (. value-node 1))) (fennel.sym? pattern))
      (bind! sc (check-name! st pattern) (define-helper st sc value-node))
      (fennel.list? pattern)
      (let [names (icollect [_ n (ipairs pattern)] (check-name! st n))
            parts (check-parts st value-node (expr st value-node))]
        (when (not= (length names) (length parts))
          (refuse st pattern (.. "binds " (length names) " names to " (length parts) " values")))
        (each [i name (ipairs names)]
          (when (not= name "_")
            (let [p (. parts i)]
              (bind! sc name {:kind :value :fn st.fn :part (if p.const p (declare! st pattern p))})))))
      (let [name (check-name! st pattern)
            parts (expr st value-node)]
        (when (not= name "_") (bind-value! st value-node sc name parts)))))

(fn let-form [st node]
  (let [bindings (. node 2)
        sc (new-scope st.scope)]
    (when (not (fennel.sequence? bindings))
      (refuse st node "(let [name value ...] body) needs its bindings in [ ]"))
    (when (= 1 (% (length bindings) 2))
      (refuse st node "let's bindings come in pairs: name value"))
    (let [saved st.scope]
      (set st.scope sc)
      (for [i 1 (length bindings) 2]
        (bind-pattern! st sc (. bindings i) (. bindings (+ i 1))))
      (let [parts (body st sc (fcollect [i 3 (length node)] (. node i)) node)]
        (set st.scope saved)
        parts))))

(fn numbers-of [st node value n]
  "The `n` numbers `value` gives (a values form, a helper's results), for names bound
or set together."
  (let [parts (check-parts st value (expr st value))]
    (when (not= n (length parts))
      (refuse st node (.. "binds " n " names to " (length parts) " values")))
    (each [_ p (ipairs parts)]
      (when (not= p.t :float) (refuse st node "several values must all be numbers")))
    parts))

(fn local-form [st node sc mutable?]
  (let [[_ pattern value] node]
    (when (not= 3 (length node))
      (refuse st node (.. "(" (if mutable? "var" "local") " name value) takes a name and a value")))
    (if mutable?
        ;; (var d 1) or (var (a b) (values 1 2)): each a new local, never a constant.
        (let [names (if (fennel.list? pattern) (icollect [_ n (ipairs pattern)] (check-name! st n))
                        [(check-name! st pattern)])
              parts (if (fennel.list? pattern) (numbers-of st node value (length names))
                        [(number-arg st value)])]
          (each [i name (ipairs names)]
            (let [p (. parts i)
                  v (declare! st node (collect [k x (pairs p)] (when (not= k :const) (values k x))))]
              (when (not= name "_") (bind! sc name {:kind :var :fn st.fn :part v})))))
        (bind-pattern! st sc pattern value))
    []))

(fn set-target [st name]
  (let [b (lookup st.scope name)]
    (when (or (not b) (not= b.kind :var))
      (refuse st nil (.. "set needs a var declared in the function (var " name " ...); `"
                         name "` is not one")))
    (when (not= b.fn st.fn)
      (refuse st nil (.. "a helper function sets `" name "` of the function around it: closures over mutable state are not supported")))
    b))

(fn set-form [st node]
  (let [[_ target value] node]
    (when (not= 3 (length node)) (refuse st node "(set name value) takes a name and a value"))
    (if (fennel.list? target)
        ;; (set (a b) (values b a)): every value is read before any var changes, as
        ;; in Lua's a, b = b, a; GLSL assigns one by one, so each value that is not
        ;; a constant goes through a new local first.
        (let [names (icollect [_ n (ipairs target)] (check-name! st n))
              bs (icollect [_ name (ipairs names)] (set-target st name))
              parts (numbers-of st node value (length names))
              held (icollect [_ p (ipairs parts)] (if p.const p (declare! st node p)))]
          (cost! st node (length names))
          (each [i b (ipairs bs)]
            (let [p (. held i)]
              (emit! st (.. b.part.g " = " p.g ";") (.. b.part.l " = " p.l))))
          [])
        (let [b (set-target st (check-name! st target))
              p (number-arg st value)]
          (cost! st node 1)
          (emit! st (.. b.part.g " = " p.g ";") (.. b.part.l " = " p.l))
          []))))

(fn for-form [st node]
  (let [spec (. node 2)]
    (when (or (not (fennel.sequence? spec)) (< (length spec) 3) (> (length spec) 4))
      (refuse st node "(for [i start stop step] ...) needs a name and two or three bounds"))
    (let [name (check-name! st (. spec 1))
          bound (fn [k]
                  (let [p (number-arg st (. spec k))]
                    (when (not (and p.const (= p.const (math.floor p.const))))
                      (refuse st node "a for loop's bounds must be whole constant numbers (the shader unrolls what it can; a loop must end)"))
                    p.const))
          start (bound 2)
          stop (bound 3)
          step (if (. spec 4) (bound 4) 1)
          turns (if (= step 0) math.huge (math.max 0 (+ 1 (math.floor (/ (- stop start) step)))))]
      (when (or (= step 0) (> turns limits.loop-turns))
        (refuse st node (.. "a for loop may turn at most " limits.loop-turns " times, this one "
                            (if (= step 0) "never ends" (.. "turns " turns " times")))))
      (let [i (fresh! st "i")
            v (fresh! st "v")
            sc (new-scope st.scope)
            saved-weight st.weight
            saved-scope st.scope]
        (count-local! st node 1)
        (bind! sc name {:kind :value :fn st.fn :part {:g v :l v :t :float}})
        (set st.weight (* st.weight (math.max turns 1)))
        (set st.scope sc)
        (let [(block) (capture st #(body st sc (fcollect [k 3 (length node)] (. node k)) node))]
          (set st.weight saved-weight)
          (set st.scope saved-scope)
          (table.insert block 1 {:g (.. "float " v " = float(" i ");")})
          (nest! st (.. "for (int " i " = " (string.format "%d" start) "; " i
                        (if (> step 0) " <= " " >= ") (string.format "%d" stop) "; " i
                        (if (= step 1) "++" (.. " += " (string.format "%d" step))) ") {")
                 (.. "for " v " = " (string.format "%d" start) ", " (string.format "%d" stop)
                     (if (= step 1) "" (.. ", " (string.format "%d" step))) " do")
                 block "}" "end")
          [])))))

(fn external-helper [st node name form resolve]
  ;; A function of the scene file outside the distance function (a top-level fn):
  ;; translated once as a helper, its own outside names looked up by its `resolve`.
  (case (. st.external form)
    :busy (refuse st node (.. "`" name "` calls itself: recursion is not supported in a distance function"))
    helper helper
    nil (let [saved st.resolve]
          (tset st.external form :busy)
          (set st.resolve resolve)
          (let [helper (define-helper st (new-scope nil) form)]
            (set st.resolve saved)
            (tset st.external form helper)
            helper))))

(fn scope-helpers [st]
  "The names of the helpers in reach, for a guess at a misspelt one."
  (let [out []]
    (var sc st.scope)
    (while sc
      (each [name b (pairs sc.names)]
        (when (= b.kind :helper) (table.insert out name)))
      (set sc sc.parent))
    (table.sort out)
    out))

(fn finite [n]
  ;; math.huge from outside the function (a (local {: huge} math)) is the huge of
  ;; math.huge itself; any other infinity or a nan is refused by `constant`.
  (if (= n math.huge) huge (= n (- math.huge)) (- huge) n))

(fn resolve-free [st node name ?call]
  "The binding of `name`, which is not bound in the function: math's (math.x), or
what the scene's resolver says of a name from outside the function. `?call`: the
name is called, and a refusal lists what may be called."
  (let [field (name:match "^math%.([%w_]+)$")]
    (if (and field (. math-constants field)) {:kind :value :part (constant st node (. math-constants field))}
        (and field (. math-functions field)) {:kind :math :name field}
        field (refuse st node (.. "`" name "` is not one of the math functions a distance function may use"
                                  (suggestion name) " (it may use " math-list ")"))
        (case (and st.resolve (st.resolve name))
          {:number n} {:kind :value :part (constant st node (finite n))}
          {:math f} (if (. math-functions f) {:kind :math :name f}
                        (refuse st node (.. "`" name "` is math." f ", which a distance function cannot use"
                                            (suggestion f) " (it may use " math-list ")")))
          ;; (local {: clamp} math): Lua's math has no clamp, so the name holds nil
          ;; when the file runs; the translation has GLSL's.
          {:nil true} (if (?. math-functions name :library) {:kind :math :name name}
                          (refuse st node (.. "`" name "` is nil from outside the function; a name from outside it may hold a number, a math function or a function of the file"
                                              (suggestion name (scope-helpers st)))))
          {:unreadable why} (refuse st node (.. "`" name "` is a function the translator cannot read: " why
                                                (if (?. math-functions name :library)
                                                    (.. "; or call math." name ", GLSL's " name)
                                                    (suggestion name))))
          {:helper form :resolve resolve} (external-helper st node name form resolve)
          {:other what} (refuse st node (.. "`" name "` is " what " from outside the function; a distance function may use numbers and math functions from outside it"))
          _ (if ?call
                (refuse st node (.. "`" name "` is not a function a distance function may call"
                                    (suggestion name (scope-helpers st))
                                    " (it may call " math-call-list ", and helper functions: (fn name [a b] ...) in the function or the file)"))
                (refuse st node (.. "`" name "` is not defined in the distance function (it may use its arguments, its own locals and helpers, math.*, and numbers or math functions named outside it)")))))))

(fn symbol [st node]
  (let [name (tostring node)]
    (when (= name "nil") (refuse st node "`nil` is not a number"))
    (case (or (lookup st.scope name) (resolve-free st node name))
      {:kind :value : part} (do (when (and (not part.const) (not= (?. (lookup st.scope name) :fn) st.fn))
                                  (refuse st node (.. "a helper function uses `" name "` of the function around it; pass it as an argument")))
                                [part])
      {:kind :var : part} (do (when (not= (. (lookup st.scope name) :fn) st.fn)
                                (refuse st node (.. "a helper function uses the var `" name "` of the function around it: closures over mutable state are not supported")))
                              [part])
      {:kind :helper} (refuse st node (.. "the helper `" name "` is used as a value; call it: (" name " ...)"))
      {:kind :recursive} (refuse st node (.. "`" name "` refers to itself: recursion is not supported in a distance function"))
      {:kind :math} (refuse st node (.. "`" name "` is used as a value; call it"))
      _ (refuse st node (.. "`" name "` cannot be used here")))))

(fn thread [st node last?]
  ;; (-> x (f a) g) is (g (f x a)); ->> puts x last: the form they stand for.
  (when (< (length node) 2) (refuse st node "(-> x ...) needs a value to thread"))
  (var acc (. node 2))
  (for [i 3 (length node)]
    (let [step (. node i)
          items (if (fennel.list? step) (icollect [_ v (ipairs step)] v) [step])
          at (if last? (+ (length items) 1) 2)]
      (table.insert items at acc)
      (set acc (fennel.list ((or table.unpack _G.unpack) items)))))
  acc)

(fn call [st node]
  (let [head (. node 1)
        name (sym-name head)]
    (if (not name)
        (refuse st node (.. "a call needs a function name first, got "
                            (if (fennel.list? head) "an expression" (tostring head))))
        (case name
          (where op (or (= op "+") (= op "-") (= op "*") (= op "/") (= op "%"))) (arithmetic st node op)
          "^" (power st node)
          (where op (. comparison-ops op)) (comparison st node op)
          (where op (or (= op "and") (= op "or") (= op "not"))) (logic st node op)
          "->" (expr st (thread st node false))
          "->>" (expr st (thread st node true))
          "if" (if-form st node)
          "when" (when-form st node)
          "do" (body st (new-scope st.scope) (args-of node) node)
          "let" (let-form st node)
          "values" (check-parts st node (values-form st node))
          "for" (for-form st node)
          "set" (set-form st node)
          "local" (refuse st node "(local ...) belongs in a body (a fn's or a let's), not inside an expression")
          "var" (refuse st node "(var ...) belongs in a body (a fn's or a let's), not inside an expression")
          "fn" (refuse st node "a helper function must be bound to a name: (fn name [a b] ...) in a body, or (let [name (fn [a b] ...)] ...)")
          _ (let [reason (. refused-forms name)]
              (if reason (not-supported st node (.. "`" (if (= name "hashfn") "#(...)" name) "`") reason)
                  (let [b (or (lookup st.scope name) (resolve-free st head name true))]
                    (case b.kind
                      :helper (helper-call st node b)
                      :math (math-call st node b.name)
                      :recursive (refuse st node (.. "`" name "` calls itself: recursion is not supported in a distance function"))
                      _ (refuse st node (.. "`" name "` is a value, not a function a distance function can call"))))))))))

(set expr
     (fn [st node]
       (let [line (line-of node)
             saved st.line]
         (when line (set st.line line))
         (let [parts (if (= (type node) :number) [(constant st node node)]
                         (fennel.sym? node) (symbol st node)
                         (fennel.list? node) (call st node)
                         (= (type node) :string) (not-supported st node "a string")
                         (= (type node) :boolean) (refuse st node (.. "`" (tostring node) "` is not a number; conditions are comparisons"))
                         (fennel.sequence? node) (not-supported st node "a [...] table" "for several numbers use (values a b c)")
                         (fennel.table? node) (not-supported st node "a {...} table")
                         (not-supported st node (.. "a " (type node))))]
           (set st.line saved)
           parts))))

(set body
     (fn [st sc forms at]
       "Translate `forms` in scope `sc`: all but the last for their effects; the last's
parts."
       (let [saved st.scope]
         (set st.scope sc)
         (var parts [])
         (each [i form (ipairs forms)]
           (let [line (line-of form)]
             (when line (set st.line line)))
           (set parts
                (if (and (fennel.list? form) (= "fn" (sym-name (. form 1))) (fennel.sym? (. form 2)))
                    (do (bind! sc (check-name! st (. form 2)) (define-helper st sc form)) [])
                    (and (fennel.list? form) (= "local" (sym-name (. form 1))))
                    (local-form st form sc false)
                    (and (fennel.list? form) (= "var" (sym-name (. form 1))))
                    (local-form st form sc true)
                    (expr st form))))
         (when (= 0 (length forms)) (refuse st at "an empty body gives no value"))
         (set st.scope saved)
         parts)))

(fn params-of [st node]
  "The fn form `node`'s name symbol (or nil), parameter names and body forms."
  (let [named? (fennel.sym? (. node 2))
        params (. node (if named? 3 2))
        start (if named? 4 3)]
    (when (not (fennel.sequence? params))
      (refuse st node "(fn [a b] ...) needs its parameters in [ ]"))
    (each [_ p (ipairs params)]
      (let [name (sym-name p)]
        (when (and name (or (= name "&") (name:find "^&")))
          (refuse st p "rest parameters (&) are not supported in a distance function"))))
    ;; A docstring (a string first, with forms after it) is not code: skipped.
    (let [first (if (and (= (type (. node start)) :string) (> (length node) start)) (+ start 1) start)]
      (values (and named? (. node 2))
              (icollect [_ p (ipairs params)] (check-name! st p))
              (fcollect [i first (length node)] (. node i))))))

(fn new-fn [st]
  (set st.fn-count (+ st.fn-count 1))
  {:id st.fn-count :locals 0})

(set define-helper
     (fn [st sc node]
       (when (>= (length st.helpers) limits.helpers)
         (refuse st node (.. "more than " limits.helpers " helper functions")))
       (let [(name-sym names forms) (params-of st node)
             ;; Named after the function: two custom functions in one shader each
             ;; have their own helpers.
             name (.. st.name "Fn" (length st.helpers))
             _ (table.insert st.helpers false)   ; its place, for the next helper's name
             slot (length st.helpers)
             saved {:fn st.fn :scope st.scope :weight st.weight :cost st.cost :out st.out}
             fsc (new-scope sc)]
         (set st.fn (new-fn st))
         (set st.weight 1)
         (set st.cost 0)
         (when name-sym (bind! fsc (tostring name-sym) {:kind :recursive}))
         (let [args (icollect [_ n (ipairs names)]
                      (let [v (fresh! st "v")]
                        (count-local! st node 1)
                        (bind! fsc n {:kind :value :fn st.fn :part {:g v :l v :t :float}})
                        v))
               (block parts) (capture st #(check-parts st node (body st fsc forms node)))
               nret (length parts)]
           (when (or (= nret 0) (accumulate [b? false _ p (ipairs parts)] (or b? (= p.t :bool))))
             (refuse st node "a helper function must return one to four numbers"))
           (let [helper {:kind :helper : name :nargs (length args) : nret :cost st.cost}
                 gargs (table.concat (icollect [_ a (ipairs args)] (.. "float " a)) ", ")
                 gret (if (= nret 1) (. parts 1 :g)
                          (.. (vec-type nret) "(" (table.concat (icollect [_ p (ipairs parts)] p.g) ", ") ")"))]
             (table.insert block {:g (.. "return " gret ";")
                                  :l (.. "return " (table.concat (icollect [_ p (ipairs parts)] p.l) ", "))})
             (tset st.helpers slot
                   {: helper
                    :item {:g (.. (vec-type nret) " " name "(" gargs ") {")
                           :l (.. "local function " name "(" (table.concat args ", ") ")")
                           : block :g-close "}" :l-close "end"}})
             ;; Written out in the order they end: a helper's body may call helpers
             ;; begun after it (one of the file, translated when first called, or
             ;; one defined in its body), and GLSL and Lua both need a function
             ;; defined before the line that calls it. No helper calls itself, so
             ;; each one's callees have ended before it does.
             (table.insert st.finished (. st.helpers slot))
             (set st.fn saved.fn)
             (set st.scope saved.scope)
             (set st.weight saved.weight)
             (set st.cost saved.cost)
             (set st.out saved.out)
             helper)))))

(local type-sizes {:float 1 :vec2 2 :vec3 3 :vec4 4})

(fn group-args [st form types vars head]
  ;; The GLSL parameters when the arguments after x y z come in vectors (a
  ;; primitive's :args): a0, a1, ... of `types`, unpacked into the v names in `head`.
  (let [out []]
    (var i 4)
    (each [k t (ipairs types)]
      (let [n (or (. type-sizes t) (refuse st form (.. "unknown argument type " (tostring t))))
            a (.. "a" (- k 1))]
        (table.insert out (.. ", " t " " a))
        (for [c 1 n]
          (when (not (. vars i))
            (refuse st form "the function takes fewer arguments than its argument types hold"))
          (table.insert head {:g (.. "float " (. vars i) " = " a
                                     (if (= n 1) "" (.. "." (. ["x" "y" "z" "w"] c))) ";")})
          (set i (+ i 1)))))
    (when (not= i (+ 1 (length vars)))
      (refuse st form "the function takes more arguments than its argument types hold"))
    (table.concat out "")))

(fn translate [form ?options]
  "GLSL and Lua for the distance function `form`, the parsed (fn [x y z ...] ...) of a
scene file. Returns {:glsl :lua :params [name ...] :cost n}: :glsl defines
`float NAME(vec3 p, float ...)` and :lua is a chunk returning the Lua function
(x y z ...); the extra arguments are the fn's parameters after x y z (:params, in
order), then, with :scale? (default true), a factor the distance is multiplied by.
On failure: nil, the reason and its line. Options: :name (the GLSL function's name,
default sdCustom), :resolve (fn [name]) -> {:number n}, {:math f}, {:helper FORM
:resolve RESOLVE} (a function of the file: its form and the resolver of its own outside
names), {:nil true} (the name holds nil), {:unreadable why} (a function whose form
cannot be found), {:other what} or nil, for names from outside the function, :scale? false for
no factor, :arg-types [:vec3 :float ...] to take the arguments after x y z in GLSL as
those vectors (a0, a1, ...; the Lua function still takes them one by one)."
  (let [options (or ?options {})
        st {:counter 0 :fn-count 0 :helpers [] :finished [] :out [] :weight 1 :cost 0 :external {}
            :scope (new-scope nil) :line (line-of form) :resolve options.resolve
            :name (or options.name "sdCustom")}
        (ok? result)
        (pcall
         (fn []
           (when (not (and (fennel.list? form) (= "fn" (sym-name (. form 1)))))
             (refuse st form "a distance function must be written (fn [x y z] ...) in the scene file"))
           (let [(name-sym names forms) (params-of st form)
                 _ (when (< (length names) 3)
                     (refuse st form "a distance function takes the point first: (fn [x y z] ...)"))
                 sc (new-scope nil)
                 main-fn (new-fn st)
                 _ (set st.fn main-fn)
                 vars (fcollect [_ 1 (length names)] (fresh! st "v"))
                 scale (when (not= false options.scale?) (fresh! st "v"))]
             (count-local! st form (length names))
             (when name-sym (bind! sc (tostring name-sym) {:kind :recursive}))
             (each [i n (ipairs names)]
               (when (not= n "_")
                 (bind! sc n {:kind :value :fn main-fn :part {:g (. vars i) :l (. vars i) :t :float}})))
             (let [(block parts) (capture st #(body st sc forms form))
                   _ (when (not= 1 (length parts))
                       (refuse st form (.. "a distance function must give one number, this one gives "
                                           (length parts) " values")))
                   d (. parts 1)
                   _ (when (not= d.t :float)
                       (refuse st form "a distance function must give a number, not a comparison"))
                   name st.name
                   head [{:g (.. "float " (. vars 1) " = p.x;")} {:g (.. "float " (. vars 2) " = p.y;")}
                         {:g (.. "float " (. vars 3) " = p.z;")}]
                   gargs (if options.arg-types
                             (group-args st form options.arg-types vars head)
                             (table.concat (icollect [i v (ipairs vars)] (when (> i 3) (.. ", float " v))) ""))
                   gscale (if scale (.. ", float " scale) "")
                   main (icollect [_ item (ipairs head)] item)]
               (each [_ item (ipairs block)] (table.insert main item))
               (table.insert main {:g (.. "return " (if scale (.. "(" d.g ") * " scale) d.g) ";")
                                   :l (.. "return " (if scale (.. "(" d.l ") * " scale) d.l))})
               (let [glsl [] lua-lines []]
                 (each [_ h (ipairs st.finished)]
                   (flatten [h.item] :g 0 glsl)
                   (flatten [h.item] :l 0 lua-lines))
                 (flatten [{:g (.. "float " name "(vec3 p" gargs gscale ") {") :block main :g-close "}"}]
                          :g 0 glsl)
                 (let [all-args (icollect [_ v (ipairs vars)] v)]
                   (when scale (table.insert all-args scale))
                   (flatten [{:l (.. "return function(" (table.concat all-args ", ") ")") :block main
                              :l-close "end"}]
                            :l 0 lua-lines))
                 {:glsl (table.concat glsl "\n") :lua (table.concat lua-lines "\n")
                  :params (fcollect [i 4 (length names)] (. names i)) :cost st.cost
                  :glsl-name name})))))]
    (if ok? result
        (and (= (type result) :table) result.translate-error)
        (values nil result.translate-error result.line)
        (error result 0))))

(fn compile-lua [text]
  "The Lua function of a translation's :lua text, loaded with only math's functions
in reach (the text calls nothing else)."
  (let [env {:math {:sqrt math.sqrt :abs math.abs :floor math.floor :ceil math.ceil
                    :sin math.sin :cos math.cos :tan math.tan :asin math.asin :acos math.acos
                    :atan math.atan :atan2 (or math.atan2 math.atan) :exp math.exp
                    :log math.log :min math.min :max math.max}}
        chunk (if _G.setfenv
                  (let [c (assert (_G.loadstring text "=custom distance"))]
                    (_G.setfenv c env)
                    c)
                  (assert (load text "=custom distance" :t env)))]
    (chunk)))

{: translate : compile-lua : limits : supported : glsl-number}

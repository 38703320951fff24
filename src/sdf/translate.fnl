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
;;   Vectors (issue 44): [a b] and [a b c]; + - * / % of vectors and numbers, component
;;   by component (a number goes to every component); math's functions and GLSL's
;;   clamp mix ... component-wise; (length v), (dot a b), (cross a b), (normalize v)
;;   (math.length ... or names taken from math); (. v 1); (let [[x y z] p] ...);
;;   vectors as helpers' arguments and values; (fn [p] ...) takes the point as one
;;   vector. Arrays of numbers or of vectors ([[0 1] [1 0] ...], in the function or a
;;   (local verts ...) of the file) indexed by (. verts i), where i is known to stay
;;   in range: a whole constant or a loop counter, plus or minus constants, % a
;;   constant, or an if of such. for takes &until (GLSL's if (c) break;) and a stop of
;;   (math.min n K) with K a whole constant: K turns at most, and a break past n.
;;
;;   Vectors are scalarised on both sides: a vector is a value {:t :vec :comps [...]}
;;   of one part per component: a GLSL vec2 or vec3 appears only in length(vec3(...)),
;;   the builtin a hand-written distance uses, and as a helper's several values. Lua has no vectors, so its side must
;;   be scalarised anyway; doing the same in GLSL keeps the one walk writing one
;;   expression per component for both texts, the same operations in the same order,
;;   and every existing mechanism (locals, if results, helpers' several values, the
;;   main process's checks of the texts, which know floats only) takes a vector as
;;   the numbers it is. An array index is a chain of selects, (i == 1.0 ? a : ...),
;;   alike in both texts (no GLSL array, no Lua table): the GLSL compiler folds it in
;;   an unrolled loop, and the check of the texts needs no new construct.
;;   Helpers are translated at their first call, once per kind of arguments
;;   (numbers or vectors of a size), each kind its own GLSL function.
;; Anything else is refused with the line and the construct. The output holds only
;; generated names (p, v0 v1 ..., i0 ... for loop counters, a0 ... for vector
;; arguments, sdCustom and its helpers sdCustomFn0 ...) and floats with a decimal
;; point (a loop counter's bounds are ints): nothing of the scene's text, and the
;; same text for the same form.

;; `pairs` under another name: a loop over `pairs` by that name is LuaJIT's ITERN,
;; which Debian 12's LuaJIT ends early once despecialised (see src/util/wire.fnl).
(local each-pair pairs)

(local fennel (require :fennel))
(local text (require :src.util.text))

(local limits
  {:loop-turns 64     ; one for loop's turns: a constant bound, unrolled or not
   ;; A for loop's bounds, its step and its counter past the last turn (which the
   ;; loop's test reads) within this in size, 2^24: the shader counts in an int of 32
   ;; bits (a bound past 2^31 overflows, and i <= 2147483647 is always true: the loop
   ;; never ends) and reads the counter as a float, whole numbers exact up to 2^24.
   :loop-bound 16777216
   ;; The GLSL text of one function (helpers included), a backstop for what the
   ;; cost does not see: text that grows faster than the operations counted.
   ;; examples/ and scenes/custom.fnl write at most 5 KB.
   :text 65536
   :cost 4000         ; operations per evaluation, loops counted by their turns
                      ; (scenes/custom.fnl: the gyroid shell cut by a sphere 25,
                      ; the six blended spheres' loop 150)
   :locals 150        ; names in one function (Lua allows 200 live locals)
   :values 4          ; values a helper returns: GLSL's vec4 at most
   :helpers 32
   :array-items 64    ; items of one array (each index is a chain of selects)
   :power 8})         ; the largest constant exponent of ^

(local supported
  "numbers, vectors [a b c] and arrays of them, let, local, var/set, if, when, do, -> ->>, values, fn helpers, for with constant bounds, + - * / % ^, comparisons, and/or/not, math functions")

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
   :max {:glsl "max"}
   ;; Of vectors only (see vector-call): GLSL's, written out alike in both texts.
   :length {:vector true :counts {1 true} :args "v"}
   :dot {:vector true :counts {2 true} :args "a b"}
   :cross {:vector true :counts {2 true} :args "a b"}
   :normalize {:vector true :counts {1 true} :args "v"}})

;; GLSL's own functions that Lua's math lacks, called as math.NAME (or a name
;; destructured from math: (local {: clamp} math), which holds nil when the file
;; runs, as the distance function is never called there). Each is written out the
;; same way in both languages (see library-call), so the CPU and the GPU agree where
;; GLSL leaves the builtin loose: round is floor(x + 0.5) (GLSL's round may go either
;; way at .5), clamp is min(max(x, lo), hi) (GLSL's is undefined for lo > hi), mod
;; is % (GLSL's mod, floored; not Lua 5.1's math.mod, an alias of fmod). :args names
;; the arguments for messages; :eval folds constant arguments.
(fn hash-value [x y z]
  ;; math.hash of numbers (see library and hash-cells).
  (let [m289 (fn [a] (- a (* 289 (math.floor (/ a 289)))))
        perm (fn [v] (m289 (* (+ (* 34 v) 1) v)))]
    (/ (perm (+ (perm (+ (perm (m289 (math.floor x))) (m289 (math.floor y)))) (m289 (math.floor z))))
       289)))

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
   :mod {:args "x y" :eval #(- $1 (* $2 (math.floor (/ $1 $2))))}
   ;; A hash of the integer cell (floor x, floor y, floor z) in [0, 1): Ashima's
   ;; permutation polynomial (34 v + 1) v mod 289, every value a whole number below
   ;; 2^24, so float32 on the GPU computes it as exactly as Lua's doubles (see
   ;; hash-parts); equal on both but for the last division by 289.
   :hash {:args "x y z" :eval #(hash-value $1 $2 $3)}
   ;; Value noise: math.hash at the 8 corners of the cell, blended by smoothstep
   ;; weights of the point's place in it (x - floor x ...): continuous, in [0, 1),
   ;; its slope at most 1.5 per unit along each axis (see noise-parts).
   :noise {:args "x y z"
                 :eval #(let [h hash-value
                              [ix iy iz] [(math.floor $1) (math.floor $2) (math.floor $3)]
                              fade (fn [t] (* t t (- 3 (* 2 t))))
                              [u v w] [(fade (- $1 ix)) (fade (- $2 iy)) (fade (- $3 iz))]
                              mix (fn [a b t] (+ (* a (- 1 t)) (* b t)))
                              at (fn [dx dy dz] (h (+ ix dx) (+ iy dy) (+ iz dz)))]
                          (mix (mix (mix (at 0 0 0) (at 1 0 0) u) (mix (at 0 1 0) (at 1 1 0) u) v)
                               (mix (mix (at 0 0 1) (at 1 0 1) u) (mix (at 0 1 1) (at 1 1 1) u) v)
                               w))}})

(each [name spec (each-pair library)]
  (let [(_ spaces) (spec.args:gsub " " "")]
    (tset math-functions name {:library true :counts {(+ spaces 1) true} :args spec.args})))

;; GLSL has no portable infinity (1.0 / 0.0 is undefined): math.huge is this large
;; number in both texts. Far beyond any scene and any draw distance, and its square
;; is still a float32 (1e60 is not: 1e30 leaves room for arithmetic).
(local huge 1e30)

(local math-constants {:pi math.pi :huge huge})

(local math-names
  ["sqrt" "abs" "floor" "ceil" "sin" "cos" "tan" "asin" "acos" "atan" "exp" "log" "pow" "min"
   "max" "clamp" "mix" "fract" "sign" "step" "smoothstep" "round" "mod" "length" "dot" "cross"
   "normalize"])

(local math-call-list
  "math.sqrt abs floor ceil sin cos tan asin acos atan exp log pow min max and GLSL's clamp mix fract sign step smoothstep round mod length dot cross normalize as math.clamp ...")

(local math-list
  "math.sqrt abs floor ceil sin cos tan asin acos atan exp log pow min max, GLSL's clamp mix fract sign step smoothstep round mod, of vectors length dot cross normalize, and math.pi huge")

;; Names authors reach for that go by another name here: the hint to give instead of
;; a guess at the spelling.
(local aliases
  {:fmod "for a remainder write (% a b) or (math.mod a b), floored as GLSL's mod (math.fmod truncates toward zero)"
   :lerp "GLSL's mix is (math.mix a b t)"
   :frac "GLSL's fract is (math.fract x)"
   :saturate "write (math.clamp x 0 1)"
   :atan2 "write (math.atan y x), GLSL's atan(y, x)"
   :sgn "write (math.sign x)"
   :trunc "write (if (< x 0) (math.ceil x) (math.floor x))"
   :modf "write (math.fract x) and (math.floor x)"
   :huge "math.huge is a value, not a function"
   :pi "math.pi is a value, not a function"})

;; Forms a reader may expect to work, with a hint at what to write instead.
(local refused-forms
  {:while "use for with constant bounds"
   :each "index an array in a numeric for: (for [i 1 n] (. items i))"
   :lambda "use fn"
   :λ "use fn"
   :hashfn "use fn"
   :tset "no tables"
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

(fn describe [p]
  "What the value `p` is, for messages."
  (case p.t
    :vec (.. "a vector of " (length p.comps) " numbers")
    :array (.. "an array of " (length p.items) " "
               (if (= :vec (. p.items 1 :t)) (.. "vectors of " (length (. p.items 1 :comps)) " numbers") "numbers"))
    :bool "a comparison"
    _ "a number"))

(fn constant-value? [p]
  "True when `p` holds constants only (a number, or a vector or array of them)."
  (case p.t
    :vec (accumulate [c? true _ c (ipairs p.comps)] (and c? (not= nil c.const)))
    :array (accumulate [c? true _ item (ipairs p.items)] (and c? (constant-value? item)))
    _ (not= nil p.const)))

(fn int-range [p]
  "[lo hi], the whole numbers `p` may hold, when known (a whole constant, a loop
counter, and + - % of such), else nil."
  (if (and p.const (= p.const (math.floor p.const))) [p.const p.const] p.range))

(fn number-arg [st node]
  (let [p (one st node (expr st node))]
    (case p.t
      :bool (refuse st node "a comparison is used as a number (and/or/not and if conditions take comparisons; arithmetic takes numbers)")
      :vec (refuse st node (.. (describe p) " is used where a number is needed; take a component, (. v 1), or (length v) or (dot a b)"))
      :array (refuse st node (.. (describe p) " is used where a number is needed; take an item, (. a i)")))
    p))

(fn value-arg [st node]
  "A number or a vector: what arithmetic and math's functions take."
  (let [p (one st node (expr st node))]
    (case p.t
      :bool (refuse st node "a comparison is used as a number (and/or/not and if conditions take comparisons; arithmetic takes numbers)")
      :array (refuse st node (.. (describe p) " is used as a value; arithmetic takes numbers and vectors: take an item, (. a i)")))
    p))

(fn bool-arg [st node]
  (let [p (one st node (expr st node) "a condition")]
    (when (not= p.t :bool)
      (refuse st node (if (= p.t :float)
                          "a condition must be a comparison like (< a b), or and/or/not of comparisons: a number is always true in Fennel and never in GLSL"
                          (.. "a condition must be a comparison like (< a b); this is " (describe p)
                              ": compare its components, (< (. v 1) 0)"))))
    p))

(fn args-of [node] (fcollect [i 2 (length node)] (. node i)))

(fn fold [st node parts op g-op l-op identity]
  (if (= 0 (length parts)) (constant st node identity)
      (accumulate [acc nil _ p (ipairs parts)]
        (if (= acc nil) p
            (and acc.const p.const) (constant st node (op acc.const p.const))
            {:g (.. "(" acc.g " " g-op " " p.g ")") :l (.. "(" acc.l " " l-op " " p.l ")")
             :t :float}))))

(var repeatable nil)

(fn vector-size [st node args what]
  ;; The size of the vectors among `args` (all one size), or nil when there is none.
  (var n nil)
  (each [_ a (ipairs args)]
    (when (= a.t :vec)
      (let [k (length a.comps)]
        (when (and n (not= n k))
          (refuse st node (.. what " mixes a vector of " n " numbers with one of " k
                              "; make them one size: [(. v 1) (. v 2)] is two of three")))
        (set n k))))
  n)

(fn per-component [st node args what f]
  "(f args plain?) for numbers `args`; with vectors among them, a vector of f of
each component (a number goes to each, computed once): f gives one part."
  (case (vector-size st node args what)
    nil (f args true)
    n (let [held (icollect [_ a (ipairs args)] (if (= a.t :vec) a (repeatable st node a)))]
        {:t :vec :comps (fcollect [k 1 n]
                          (f (icollect [_ a (ipairs held)] (if (= a.t :vec) (. a.comps k) a)) false))})))

(fn range-of [op args]
  ;; The whole numbers + - % of whole `args` give, when all are known.
  (let [rs (icollect [_ a (ipairs args)] (int-range a))]
    (when (and (= (length rs) (length args)) (> (length rs) 0))
      (case op
        "+" [(accumulate [s 0 _ [lo] (ipairs rs)] (+ s lo)) (accumulate [s 0 _ [_ hi] (ipairs rs)] (+ s hi))]
        "-" (if (= 1 (length rs)) (let [[[lo hi]] rs] [(- hi) (- lo)])
                (let [[[lo hi]] rs]
                  [(- lo (accumulate [s 0 i [_ h] (ipairs rs)] (if (> i 1) (+ s h) s)))
                   (- hi (accumulate [s 0 i [l] (ipairs rs)] (if (> i 1) (+ s l) s)))]))
        "%" (let [[_ [m m2]] rs]
              (when (and (= 2 (length rs)) (= m m2) (> m 0)) [0 (- m 1)]))))))

(fn scalar-arithmetic [st node op args]
  (cost! st node (math.max 1 (- (length args) 1)))
  (let [p (case op
            "+" (fold st node args #(+ $1 $2) "+" "+" 0)
            "*" (fold st node args #(* $1 $2) "*" "*" 1)
            "-" (if (= 0 (length args)) (refuse st node "(-) needs an argument")
                    (= 1 (length args))
                    (let [a (. args 1)]
                      (if a.const (constant st node (- a.const))
                          {:g (.. "(-" a.g ")") :l (.. "(-" a.l ")") :t :float}))
                    (fold st node args #(- $1 $2) "-" "-" 0))
            "/" (if (= 0 (length args)) (refuse st node "(/) needs an argument")
                    (= 1 (length args)) (fold st node [(constant st node 1) (. args 1)] #(/ $1 $2) "/" "/" 1)
                    (fold st node args #(/ $1 $2) "/" "/" 1))
            "%" (if (not= 2 (length args)) (refuse st node "(% a b) takes two arguments")
                    (let [[a b] args]
                      {:g (.. "mod(" a.g ", " b.g ")") :l (.. "(" a.l " % " b.l ")") :t :float})))
        r (and (not p.const) (range-of op args))]
    (if r (doto (collect [k v (each-pair p)] k v) (tset :range r)) p)))

(fn arithmetic [st node op]
  ;; Of numbers, or component-wise of vectors (a number goes to every component).
  (let [args (icollect [_ a (ipairs (args-of node))] (value-arg st a))]
    [(per-component st node args (.. "(" op " ...)") #(scalar-arithmetic st node op $1))]))

(fn declare! [st node part]
  "A new local holding `part`'s value; its name as a part."
  (let [name (fresh! st "v")]
    (count-local! st node)
    (emit! st (.. (if (= part.t :bool) "bool " "float ") name " = " part.g ";")
           (.. "local " name " = " part.l))
    {:g name :l name :t part.t :range part.range}))

(fn hold [st node p]
  "`p` in new locals (constants stay inline): a value bound to a name keeps what it
was when bound. A vector or an array, component by component."
  (case p.t
    :vec {:t :vec :comps (icollect [_ c (ipairs p.comps)] (hold st node c))}
    :array {:t :array :items (icollect [_ item (ipairs p.items)] (hold st node item))}
    _ (if p.const p (declare! st node p))))

(fn power [st node]
  ;; (^ a n) of a number or, component by component, of a vector.
  (let [args (args-of node)]
    (when (not= 2 (length args)) (refuse st node "(^ a n) takes two arguments"))
    (let [base (value-arg st (. args 1))
          n (. (number-arg st (. args 2)) :const)]
      (when (not (and n (= n (math.floor n)) (<= 0 n limits.power)))
        (refuse st node (.. "(^ a n) needs a whole constant n from 0 to " limits.power
                            "; for other powers use (math.pow a b), with a >= 0")))
      [(per-component st node [base] "(^ ...)"
                      (fn [[b]]
                        (cost! st node (math.max 1 (- n 1)))
                        (if (= n 0) (constant st node 1)
                            b.const (constant st node (^ b.const n))
                            (let [b (if (= n 1) b (declare! st node b))]
                              (fold st node (fcollect [_ 1 n] b) #(* $1 $2) "*" "*" 1)))))])))

(local comparison-ops {"<" ["<" "<"] ">" [">" ">"] "<=" ["<=" "<="] ">=" [">=" ">="]
                       "=" ["==" "=="] "not=" ["!=" "~="] "~=" ["!=" "~="]})

(fn comparison [st node op]
  (let [args (icollect [_ a (ipairs (args-of node))] (number-arg st a))
        [g-op l-op] (. comparison-ops op)]
    (when (< (length args) 2) (refuse st node (.. "(" op " ...) needs two or more arguments")))
    (when (and (> (length args) 2) (or (= op "not=") (= op "~=")))
      (refuse st node (.. "(" op " a b) takes two arguments")))
    (cost! st node (- (length args) 1))
    ;; A middle operand of a chain is read by two comparisons: held in a local (a name
    ;; or a constant stays as it is), so that its text is written once. Written out
    ;; twice, an operand that holds a chain doubles at each link: 13 nested links of a
    ;; 400-byte file wrote 297 KB of GLSL.
    (for [i 2 (- (length args) 1)]
      (let [a (. args i)]
        (when (not (or a.const (a.g:match "^[%w_]+$")))
          (tset args i (declare! st node a)))))
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

(set repeatable
     (fn [st node p]
       "`p` itself when its text may be written twice (a constant or a name), else a
new local holding it: an argument a library function reads twice is computed once. A
vector's components each so."
       (if (= p.t :vec) {:t :vec :comps (icollect [_ c (ipairs p.comps)] (repeatable st node c))}
           (= p.t :array) p
           (or p.const (and (p.g:match "^[%w_]+[.xyzw]*$") (p.l:match "^[%w_]+$"))) p
           (declare! st node p))))

(fn sign-part [st node p]
  ;; GLSL's sign(); in Lua the same three cases (a number is never false in Lua).
  (let [x (repeatable st node p)]
    {:g (.. "sign(" x.g ")") :l (.. "(" x.l " > 0 and 1 or (" x.l " < 0 and -1 or 0))")
     :t :float}))

(fn m289-part [st node a*]
  ;; Part `a*` (a whole number below 2^24) mod 289, in [0, 289). GLSL's a / 289.0
  ;; may be off by an ulp (2.5 allowed), so its remainder is brought back into
  ;; [0, 289) by one step either way; Lua's never needs it.
  (let [a (repeatable st node a*)
        m (declare! st node {:g (.. "(" a.g " - (289.0 * floor(" a.g " / 289.0)))")
                             :l (.. "(" a.l " - (289 * math.floor(" a.l " / 289)))") :t :float})]
    (declare! st node {:g (.. "((" m.g " >= 289.0) ? (" m.g " - 289.0) : ((" m.g " < 0.0) ? (" m.g " + 289.0) : " m.g "))")
                       :l (.. "(" m.l " >= 289 and (" m.l " - 289) or (" m.l " < 0 and (" m.l " + 289) or " m.l "))")
                       :t :float})))

(fn hash-cells [st node cx cy cz]
  ;; math.hash of a cell given as parts already mod 289 (see library): each step a
  ;; whole number below 2^24, exact in float32.
  (fn perm [v]
    (m289-part st node {:g (.. "(((34.0 * " v.g ") + 1.0) * " v.g ")") :l (.. "(((34 * " v.l ") + 1) * " v.l ")")
                        :t :float}))
  (fn plus [a b] {:g (.. "(" a.g " + " b.g ")") :l (.. "(" a.l " + " b.l ")") :t :float})
  (let [h (perm (plus (perm (plus (perm cx) cy)) cz))]
    {:g (.. "(" h.g " / 289.0)") :l (.. "(" h.l " / 289)") :t :float}))

(fn hash-parts [st node x y z]
  ;; math.hash of parts x y z: the hash of their cell (floor), mod 289.
  (let [cell (fn [a] (m289-part st node {:g (.. "floor(" a.g ")") :l (.. "math.floor(" a.l ")") :t :float}))]
    (hash-cells st node (cell x) (cell y) (cell z))))

(fn noise-parts [st node x* y* z*]
  ;; math.noise of parts x y z (see library): the cell's corner (floor), the
  ;; smoothstep weights of the point's place in the cell, math.hash at the 8
  ;; corners (each coordinate's cell and the next, mod 289, once), blended as
  ;; GLSL's mix.
  (let [[x y z] (icollect [_ a (ipairs [x* y* z*])] (repeatable st node a))
        corner (icollect [_ a (ipairs [x y z])]
                 (declare! st node {:g (.. "floor(" a.g ")") :l (.. "math.floor(" a.l ")") :t :float}))
        weight (icollect [i a (ipairs [x y z])]
                 (let [f (declare! st node {:g (.. "(" a.g " - " (. corner i :g) ")")
                                            :l (.. "(" a.l " - " (. corner i :l) ")") :t :float})]
                   (declare! st node {:g (.. "((" f.g " * " f.g ") * (3.0 - (2.0 * " f.g ")))")
                                      :l (.. "((" f.l " * " f.l ") * (3 - (2 * " f.l ")))") :t :float})))
        ;; Each corner's cells mod 289, and the next ones', once.
        cells (icollect [_ c (ipairs corner)]
                (let [lo (m289-part st node c)]
                  [lo (m289-part st node {:g (.. "(" lo.g " + 1.0)") :l (.. "(" lo.l " + 1)") :t :float})]))
        at (fn [dx dy dz]
             (declare! st node (hash-cells st node (. cells 1 (+ dx 1)) (. cells 2 (+ dy 1))
                                           (. cells 3 (+ dz 1)))))
        mix (fn [a b t] {:g (.. "((" a.g " * (1.0 - " t.g ")) + (" b.g " * " t.g "))")
                         :l (.. "((" a.l " * (1 - " t.l ")) + (" b.l " * " t.l "))") :t :float})
        [u v w] weight]
    (mix (mix (mix (at 0 0 0) (at 1 0 0) u) (mix (at 0 1 0) (at 1 1 0) u) v)
         (mix (mix (at 0 0 1) (at 1 0 1) u) (mix (at 0 1 1) (at 1 1 1) u) v)
         w)))

(fn library-call [st node fname args]
  ;; GLSL's functions of `library`, written out alike in both languages; constant
  ;; arguments fold.
  (let [costs {:clamp 2 :mix 3 :fract 1 :sign 2 :step 1 :smoothstep 7 :round 1 :mod 2 :hash 50
               :noise 450}
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
                 [{:g (.. "mod(" x.g ", " y.g ")") :l (.. "(" x.l " % " y.l ")") :t :float}])
          :hash (let [[x y z] args] [(hash-parts st node x y z)])
          :noise (let [[x y z] args] [(noise-parts st node x y z)])))))

(fn scalar-math [st node fname args plain?]
  ;; One call of math's `fname` on numbers `args`: a part. `plain?`: args are the
  ;; node's own (not a vector's components), for sqrt's length() below.
  (let [spec (. math-functions fname)
        n (length args)]
    (when (not spec.library) (cost! st node (math.max 1 (- n 1))))
    (if spec.library (. (library-call st node fname args) 1)
        (or (= fname :min) (= fname :max))
        (accumulate [acc nil _ p (ipairs args)]
          (if acc {:g (.. fname "(" acc.g ", " p.g ")") :l (.. "math." fname "(" acc.l ", " p.l ")")
                   :t :float}
              p))
        (let [gs (table.concat (icollect [_ a (ipairs args)] a.g) ", ")
              ls (table.concat (icollect [_ a (ipairs args)] a.l) ", ")
              ;; The square root of a sum of squares is GLSL's length(), as a
              ;; hand-written distance says it (the same rounding as length(p)).
              lengths (when (and plain? (= fname :sqrt)) (squared-names (. node 2)))]
          {:g (if lengths
                  (.. "length(vec" (length lengths) "("
                      (table.concat (icollect [_ n (ipairs lengths)] (. (number-arg st n) :g)) ", ")
                      "))")
                  (.. spec.glsl "(" gs ")"))
           :l (if (= fname :pow) (.. "(" (. args 1 :l) " ^ " (. args 2 :l) ")")
                  (.. (if (and (= fname :atan) (= n 2)) "math.atan2" (.. "math." fname)) "(" ls ")"))
           :t :float}))))

(fn sum-of-products [st node as bs]
  ;; a1 b1 + a2 b2 + ..., left to right, the same text in both languages.
  (fold st node (icollect [k a (ipairs as)]
                  (let [b (. bs k)]
                    {:g (.. "(" a.g " * " b.g ")") :l (.. "(" a.l " * " b.l ")") :t :float}))
        #(+ $1 $2) "+" "+" 0))

(fn vector-call [st node fname args]
  ;; GLSL's length dot cross normalize: vectors in, a number or a vector out.
  (let [vec (fn [k]
              (let [a (. args k)]
                (when (not= a.t :vec)
                  (refuse st node (.. "(" fname " " (. math-functions fname :args) ") takes vectors; its argument "
                                      k " is " (describe a)
                                      (if (or (= fname :length) (= fname :normalize))
                                          "; for a number use (math.abs x)" ""))))
                a))
        same (fn [a b]
               (when (not= (length a.comps) (length b.comps))
                 (refuse st node (.. "(" fname " a b) takes two vectors of one size, got "
                                     (describe a) " and " (describe b))))
               (length a.comps))
        len (fn [v]
              ;; GLSL's length(); in Lua the square root of the sum of squares.
              (let [v (repeatable st node v)
                    n (length v.comps)
                    sq (sum-of-products st node v.comps v.comps)]
                (cost! st node (* 2 n))
                (if sq.const (constant st node (math.sqrt sq.const))
                    {:g (.. "length(vec" n "(" (table.concat (icollect [_ c (ipairs v.comps)] c.g) ", ") "))")
                     :l (.. "math.sqrt(" sq.l ")") :t :float})))]
    (case fname
      :length (len (vec 1))
      :dot (let [a (vec 1) b (vec 2)]
             (cost! st node (* 2 (same a b)))
             (sum-of-products st node a.comps b.comps))
      :cross (let [a (repeatable st node (vec 1)) b (repeatable st node (vec 2))]
               (when (or (not= 3 (length a.comps)) (not= 3 (length b.comps)))
                 (refuse st node (.. "(cross a b) takes two vectors of 3 numbers, got " (describe a)
                                     " and " (describe b))))
               (cost! st node 9)
               (let [[a1 a2 a3] a.comps [b1 b2 b3] b.comps
                     term (fn [p q r s] (scalar-arithmetic st node "-" [(scalar-arithmetic st node "*" [p q])
                                                                         (scalar-arithmetic st node "*" [r s])]))]
                 {:t :vec :comps [(term a2 b3 a3 b2) (term a3 b1 a1 b3) (term a1 b2 a2 b1)]}))
      :normalize (let [v (repeatable st node (vec 1))
                       l (let [p (len v)] (if p.const p (declare! st node p)))]
                   (cost! st node (length v.comps))
                   {:t :vec :comps (icollect [_ c (ipairs v.comps)] (scalar-arithmetic st node "/" [c l]))}))))

(fn math-call [st node fname]
  (let [spec (. math-functions fname)
        args (icollect [_ a (ipairs (args-of node))] (value-arg st a))
        n (length args)]
    (when (if spec.counts (not (. spec.counts n)) (= n 0))
      (refuse st node (.. "math." fname " takes "
                          (if (= fname :atan) "1 or 2 arguments (atan y x)"
                              spec.args (let [(_ k) (spec.args:gsub " " "")]
                                          (.. (+ k 1) " argument" (if (> k 0) "s" "")
                                              " (math." fname " " spec.args ")"))
                              (not spec.counts) "one or more arguments"
                              (. spec.counts 2) "2 arguments" "1 argument")
                          ", got " n)))
    (if spec.vector [(vector-call st node fname args)]
        [(per-component st node args (.. "(math." fname " ...)")
                        #(scalar-math st node fname $1 $2))])))

(fn length-form [st node]
  ;; Fennel's length of a table is its count of items; of a vector here, GLSL's
  ;; length(): the distance a Shadertoy author means.
  (let [args (args-of node)]
    (when (not= 1 (length args)) (refuse st node (.. "(length v) takes one vector, got " (length args) " arguments")))
    [(vector-call st node :length [(value-arg st (. args 1))])]))

(fn sequence-form [st node]
  ;; [a b] and [a b c] of numbers: a vector; of 1 or more than 3 numbers, or of
  ;; vectors of one size: an array, to index.
  (let [n (length node)]
    (when (= n 0) (refuse st node "an empty [] has no value; a vector is [a b] or [a b c]"))
    (when (> n limits.array-items)
      (refuse st node (.. "an array of " n " items; at most " limits.array-items)))
    (let [items (fcollect [i 1 n]
                  (let [p (one st (. node i) (expr st (. node i)) "an item of [...]")]
                    (when (or (= p.t :bool) (= p.t :array))
                      (refuse st (. node i) (.. "an item of [...] is " (describe p)
                                                "; items are numbers, or vectors of one size")))
                    p))
          vectors (icollect [_ p (ipairs items)] (when (= p.t :vec) p))]
      (if (= 0 (length vectors))
          (if (<= 2 n 3) [{:t :vec :comps items}] [{:t :array :items items}])
          (do (when (not= (length vectors) n)
                (refuse st node "an array mixes numbers and vectors; items are all numbers or all vectors of one size"))
              (vector-size st node items "an array")
              [{:t :array :items items}])))))

(fn select-chain [st node items index lo]
  ;; (index == lo ? items[1] : index == lo + 1 ? items[2] : ... : the last), of
  ;; numbers; written alike in both texts (a number is never false in Lua).
  (let [n (length items)]
    (cost! st node (- n 1))
    (var acc (. items n))
    (for [k (- n 1) 1 -1]
      (let [item (. items k)
            at (+ lo k -1)]
        (set acc {:g (.. "((" index.g " == " (glsl-number at) ") ? " item.g " : " acc.g ")")
                  :l (.. "(" index.l " == " (lua-number at) " and " item.l " or " acc.l ")")
                  :t :float})))
    acc))

(fn index-part [st node p i]
  ;; Item `i` (a part) of vector or array `p`.
  (let [items (case p.t
                :vec p.comps
                :array p.items
                _ (refuse st node (.. "(. v i) takes an item of a vector or an array; this is " (describe p))))
        n (length items)
        r (int-range i)]
    (when (not r)
      (refuse st node "an index must be known to stay in range: a whole constant, or a loop counter (plus or minus whole constants, % a whole constant, or an if of such)"))
    (let [[lo hi] r]
      (when (and (<= lo hi) (or (< lo 1) (> hi n)))
        (refuse st node (.. "the index may be " lo (if (= lo hi) "" (.. " to " hi)) ", outside "
                            (describe p) " (items 1 to " n ")")))
      ;; lo > hi: on a branch never taken (see narrow); any item will do.
      (if (> lo hi) (. items 1)
          (= lo hi) (. items lo)
          (let [index (repeatable st node i)
                slice (fcollect [k lo hi] (. items k))]
            (if (= :vec (. slice 1 :t))
                {:t :vec :comps (fcollect [c 1 (length (. slice 1 :comps))]
                                  (select-chain st node (icollect [_ v (ipairs slice)] (. v.comps c)) index lo))}
                (select-chain st node slice index lo)))))))

(fn index-form [st node]
  ;; (. v i) and (. verts i 1).
  (let [args (args-of node)]
    (when (< (length args) 2) (refuse st node "(. v i) takes a vector or an array and an index"))
    (var p (one st (. args 1) (expr st (. args 1))))
    (for [k 2 (length args)]
      (set p (index-part st (. args k) p (number-arg st (. args k)))))
    [p]))

(fn values-form [st node]
  (icollect [_ a (ipairs (args-of node))] (value-arg st a)))

(fn vec-type [n] (if (= n 1) "float" (.. "vec" n)))

(fn flat [st node parts]
  "The numbers (or comparisons) of `parts`, each vector's components in order, and
the shape to put them back with `unflat`: per value 0 (one) or a vector's size."
  (let [out []
        shape []]
    (each [_ p (ipairs parts)]
      (case p.t
        :vec (do (table.insert shape (length p.comps))
                 (each [_ c (ipairs p.comps)] (table.insert out c)))
        :array (refuse st node (.. (describe p) " cannot be the value of an if or a function; bind it with local and take its items, (. a i)"))
        _ (do (table.insert shape 0) (table.insert out p))))
    (values out shape)))

(fn unflat [numbers shape]
  "The values of `numbers` in `shape` (see flat)."
  (var i 0)
  (icollect [_ n (ipairs shape)]
    (if (= n 0)
        (do (set i (+ i 1)) (. numbers i))
        (let [v {:t :vec :comps (fcollect [k 1 n] (. numbers (+ i k)))}]
          (set i (+ i n))
          v))))

(var instance nil)

(fn helper-call [st node b]
  ;; A call of the helper `b` (a binding of its form): its translation for these
  ;; kinds of arguments, the arguments one number each, the values put back in shape.
  (let [args (icollect [_ a (ipairs (args-of node))] (value-arg st a))]
    (when (not= (length args) b.nargs)
      (refuse st node (.. "a helper function takes " b.nargs " arguments, given "
                          (length args))))
    (let [helper (instance st node b args)
          numbers (flat st node args)]
      (set st.cost (+ st.cost (* st.weight helper.cost)))
      (cost! st node 1)
      (let [gs (.. helper.name "(" (table.concat (icollect [_ a (ipairs numbers)] a.g) ", ") ")")
            ls (.. helper.name "(" (table.concat (icollect [_ a (ipairs numbers)] a.l) ", ") ")")]
        (if (= helper.nret 1) (unflat [{:g gs :l ls :t :float}] helper.shape)
            ;; Several values: a vector in GLSL, as many locals in Lua.
            (let [v (fresh! st "v")
                  names (fcollect [_ 1 helper.nret] (fresh! st "v"))]
              (count-local! st node helper.nret)
              (emit! st (.. (vec-type helper.nret) " " v " = " gs ";")
                     (.. "local " (table.concat names ", ") " = " ls))
              (unflat (icollect [i name (ipairs names)]
                        {:g (.. v "." (. ["x" "y" "z" "w"] i)) :l name :t :float})
                      helper.shape)))))))

(fn check-parts [st node parts]
  ;; What a value may be: numbers and vectors (at most 4 numbers in all), or one
  ;; comparison.
  (let [(numbers) (flat st node parts)]
    (when (> (length numbers) limits.values)
      (refuse st node (.. "gives " (length numbers) " numbers; at most " limits.values
                          " (a vector counts its components)")))
    (when (and (> (length numbers) 1) (accumulate [b? false _ p (ipairs numbers)] (or b? (= p.t :bool))))
      (refuse st node "several values must all be numbers")))
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

(local flipped {"<" ">" ">" "<" "<=" ">=" ">=" "<=" "=" "=" "not=" "not=" "~=" "not="})
(local negated {"<" ">=" ">" "<=" "<=" ">" ">=" "<" "=" "not=" "not=" "=" "~=" "="})

(fn narrow [st c-node true?]
  ;; The name a comparison (op name K) or (op K name) of a whole-valued name bounds,
  ;; and the range it leaves that name where the comparison is `true?`.
  (when (and (fennel.list? c-node) (= 3 (length c-node)) (. flipped (sym-name (. c-node 1))))
    (let [[head a b] c-node
          op (sym-name head)
          (name k op) (if (and (sym-name a) (= (type b) :number)) (values (sym-name a) b op)
                          (and (sym-name b) (= (type a) :number)) (values (sym-name b) a (. flipped op)))
          binding (and name (lookup st.scope name))
          r (and binding (= binding.kind :value) binding.part.range)]
      (when r
        (let [[lo hi] r
              whole? (= k (math.floor k))]
          (values name binding
                  (case (if true? op (. negated op))
                    "=" (if whole? [(math.max lo k) (math.min hi k)] [lo (- lo 1)])
                    (where (or "not=" "~=")) (if (= k lo hi) [lo (- lo 1)] (= k lo) [(+ lo 1) hi] (= k hi) [lo (- hi 1)] [lo hi])
                    "<" [lo (math.min hi (- (math.ceil k) 1))]
                    "<=" [lo (math.min hi (math.floor k))]
                    ">" [(math.max lo (+ (math.floor k) 1)) hi]
                    ">=" [(math.max lo (math.ceil k)) hi])))))))

(fn narrowed [st conds f]
  ;; (f) in a scope where each whole-valued name the conditions `conds` ([node true?]
  ;; pairs) bound has the range they leave it: in (if (= i 1) n (- i 1)), i - 1 is
  ;; at least 1 (an index's range, see index-part).
  (let [sc (new-scope st.scope)
        saved st.scope]
    (set st.scope sc)
    (each [_ [c true?] (ipairs conds)]
      (case (narrow st c true?)
        (name binding r) (bind! sc name (doto (collect [k v (each-pair binding)] k v)
                                          (tset :part (doto (collect [k v (each-pair binding.part)] k v)
                                                        (tset :range r)))))))
    (let [(block value) (capture st f)]
      (set st.scope saved)
      (values block value))))

(fn if-chain [st node]
  (let [args (args-of node)
        n (length args)]
    (when (< n 2) (refuse st node "(if c a b) needs a condition and branches"))
    (when (= 0 (% n 2))
      (refuse st node "an if needs an else branch (the last argument): a distance has a value everywhere"))
    ;; Each condition's own lines and the branches' lines, captured apart.
    ;; A vector is its components here (see flat): the branches' shapes must agree.
    (let [branch (fn [k]
                   (let [conds (fcollect [i 1 (- k 1) 2] [(. args i) (= i (- k 1))])
                         (block parts) (narrowed st conds #(check-parts st (. args k) (expr st (. args k))))
                         (numbers shape) (flat st (. args k) parts)]
                     (values block numbers (table.concat shape " "))))
          arms (fcollect [i 1 (- n 1) 2]
                 (let [(cblock c) (capture st #(bool-arg st (. args i)))
                       (bblock b shape) (branch (+ i 1))]
                   {: cblock : c : bblock : b : shape}))
          (eblock e eshape) (branch n)
          shape (icollect [k (eshape:gmatch "%d+")] (tonumber k))
          width (length e)]
      (each [_ arm (ipairs arms)]
        (when (or (not= width (length arm.b)) (not= arm.shape eshape)
                  (accumulate [bad? false i p (ipairs arm.b)] (or bad? (not= p.t (. e i :t)))))
          (refuse st node "the branches of an if give different kinds or numbers of values")))
      ;; No value at all: an if for its sets, in a body.
      (cost! st node (length arms))
      (if (and (= width 1) (= 0 (length eblock))
               (accumulate [simple? true _ arm (ipairs arms)]
                 (and simple? (= 0 (length arm.cblock)) (= 0 (length arm.bblock)))))
          ;; Expressions only: the conditional expression (a number is never false in
          ;; Lua, so `c and a or b` is c ? a : b).
          (let [ranges (icollect [_ arm (ipairs arms)] (int-range (. arm.b 1)))
                ;; The union of the branches' ranges, but those of branches never
                ;; taken (lo > hi, see narrow).
                r (when (and (= (length ranges) (length arms)) (int-range (. e 1)))
                    (accumulate [acc nil _ [l h] (ipairs (doto ranges (table.insert (int-range (. e 1)))))]
                      (if (> l h) acc
                          acc [(math.min (. acc 1) l) (math.max (. acc 2) h)]
                          [l h])))
                part (accumulate [acc (. e 1) i (ipairs arms)]
                       (let [arm (. arms (- (length arms) i -1))
                             b (. arm.b 1)]
                         {:g (.. "(" arm.c.g " ? " b.g " : " acc.g ")")
                          :l (.. "(" arm.c.l " and " b.l " or " acc.l ")") :t acc.t}))]
            (set part.range r)
            (unflat [part] shape))
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
            (unflat results shape))))))

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
    (bind! sc name {:kind :value :fn st.fn :part (hold st node p)})))

(fn bind-part! [st sc pattern p node ?as-is]
  "Bind `pattern` (a name, or [a b c] of patterns, to take a vector or an array apart)
in `sc` to the value `p`, held in locals unless `?as-is` (a helper's arguments)."
  (if (fennel.sequence? pattern)
      (let [items (case p.t
                    :vec p.comps
                    :array p.items
                    _ (refuse st pattern (.. "a [...] pattern takes a vector or an array apart; this value is "
                                             (describe p))))]
        (when (> (length pattern) (length items))
          (refuse st pattern (.. "the pattern takes " (length pattern) " items from " (describe p))))
        (each [i sub (ipairs pattern)]
          (bind-part! st sc sub (. items i) node ?as-is)))
      (let [name (if (= (type pattern) :string) pattern (check-name! st pattern))]
        (when (not= name "_")
          (bind! sc name {:kind :value :fn st.fn :part (if ?as-is p (hold st node p))})))))

(var helper-binding nil)

(fn bind-pattern! [st sc pattern value-node]
  (if (and (fennel.list? value-node) (= "fn" (sym-name (. value-node 1))) (fennel.sym? pattern))
      (let [name (check-name! st pattern)]
        (bind! sc name (helper-binding st sc value-node name)))
      (fennel.sequence? pattern)
      (bind-part! st sc pattern (one st value-node (expr st value-node)) value-node)
      (fennel.list? pattern)
      (let [names (icollect [_ n (ipairs pattern)] (check-name! st n))
            parts (check-parts st value-node (expr st value-node))]
        (when (not= (length names) (length parts))
          (refuse st pattern (.. "binds " (length names) " names to " (length parts) " values")))
        (each [i name (ipairs names)]
          (when (not= name "_")
            (let [p (. parts i)]
              (bind! sc name {:kind :value :fn st.fn :part (hold st pattern p)})))))
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
        ;; A vector var: a new local per component.
        (let [names (if (fennel.list? pattern) (icollect [_ n (ipairs pattern)] (check-name! st n))
                        [(check-name! st pattern)])
              parts (if (fennel.list? pattern) (numbers-of st node value (length names))
                        [(value-arg st value)])
              new-local (fn [p] (declare! st node (collect [k x (each-pair p)] (when (and (not= k :const) (not= k :range)) (values k x)))))]
          (each [i name (ipairs names)]
            (let [p (. parts i)
                  v (if (= p.t :vec) {:t :vec :comps (icollect [_ c (ipairs p.comps)] (new-local c))}
                        (new-local p))]
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
        (let [name (check-name! st target)
              b (set-target st name)
              p (value-arg st value)]
          (when (not= (describe p) (describe b.part))
            (refuse st node (.. "set gives " (describe p) " to `" name "`, which holds " (describe b.part)
                                "; a var keeps its kind")))
          (if (= p.t :vec)
              ;; Component by component; a component's new value that reads one set
              ;; before it goes through a new local first (as (set (a b) ...)).
              (let [targets b.part.comps
                    reads? (fn [c k]
                             (accumulate [r? false j t (ipairs targets)]
                               (or r? (and (< j k) (not= nil (c.l:find (.. "%f[%w_]" t.l "%f[^%w_]")))))))
                    early? (accumulate [r? false k c (ipairs p.comps)] (or r? (reads? c k)))
                    held (icollect [_ c (ipairs p.comps)] (if (or c.const (not early?)) c (declare! st node c)))]
                (cost! st node (length targets))
                (each [k t (ipairs targets)]
                  (let [c (. held k)]
                    (emit! st (.. t.g " = " c.g ";") (.. t.l " = " c.l)))))
              (do (cost! st node 1)
                  (emit! st (.. b.part.g " = " p.g ";") (.. b.part.l " = " p.l))))
          []))))

(fn whole-text [n]
  ;; A whole number for a message: its digits, or %g past 1e15 (1e308 has 309).
  (if (< (math.abs n) 1e15) (string.format "%d" n) (string.format "%g" n)))

(fn capped-stop [st node stop-node step]
  ;; A stop of (math.min n K ...) (step > 0) or (math.max n K ...) (step < 0), K whole
  ;; constants: the bound K of the turns, and the rest's value, or nil.
  (when (fennel.list? stop-node)
    (let [head (sym-name (. stop-node 1))
          b (and head (not (head:find ":")) (not (. refused-forms head))
                 (or (lookup st.scope head)
                     (and (head:match "^math%.[%w_]+$") (. math-functions (head:sub 6))
                          {:kind :math :name (head:sub 6)})
                     (and st.resolve (case (st.resolve head) {:math f} {:kind :math :name f}))))
          want (if (> step 0) :min :max)]
      (when (and b (= b.kind :math) (= b.name want) (>= (length stop-node) 3))
        (let [args (icollect [_ a (ipairs (args-of stop-node))] (number-arg st a))
              ks (icollect [_ a (ipairs args)] (when (and a.const (= a.const (math.floor a.const))) a.const))
              rest (icollect [_ a (ipairs args)] (when (not (and a.const (= a.const (math.floor a.const)))) a))]
          (when (and (> (length ks) 0) (> (length rest) 0))
            (values ((. math want) ((or table.unpack _G.unpack) ks))
                    (declare! st node (scalar-math st stop-node want rest false)))))))))

(fn for-form [st node]
  (let [spec (. node 2)
        until-at (when (fennel.sequence? spec)
                   (accumulate [at nil k v (ipairs spec)]
                     (or at (when (or (= (sym-name v) "&until") (= v "until")) k))))
        until-node (when until-at (. spec (+ until-at 1)))
        nbounds (if until-at (- until-at 1) (and (fennel.sequence? spec) (length spec)))]
    (when (or (not (fennel.sequence? spec)) (< nbounds 3) (> nbounds 4)
              (and until-at (not= (length spec) (+ until-at 1))))
      (refuse st node "(for [i start stop step &until c] ...) needs a name and two or three bounds (&until and its condition last)"))
    (let [name (check-name! st (. spec 1))
          whole (fn [k]
                  (let [p (number-arg st (. spec k))]
                    (when (not (and p.const (= p.const (math.floor p.const))))
                      (refuse st node "a for loop's bounds must be whole constant numbers, or a stop of (math.min n K) for at most K turns, K a whole constant (the shader needs a bound on the turns; a loop must end)"))
                    p.const))
          start (whole 2)
          step (if (= nbounds 4) (whole 4) 1)
          (capped cap-value) (capped-stop st node (. spec 3) step)
          stop (or capped (whole 3))
          turns (if (= step 0) math.huge (math.max 0 (+ 1 (math.floor (/ (- stop start) step)))))
          last (+ start (* step (- turns 1)))]
      (when (or (= step 0) (> turns limits.loop-turns))
        (refuse st node (.. "a for loop may turn at most " limits.loop-turns " times, this one "
                            (if (= step 0) "never ends" (.. "turns " (whole-text turns) " times")))))
      (let [reach (accumulate [far 0 _ v (ipairs [start stop step (+ last step)])]
                    (if (> (math.abs v) (math.abs far)) v far))]
        (when (> (math.abs reach) limits.loop-bound)
          (refuse st node (.. "a for loop's counter must stay within -" limits.loop-bound " to "
                              limits.loop-bound " (2^24: the shader counts in a 32-bit int, read as a float exact only so far), this one reaches "
                              (whole-text reach)
                              "; count from a small number and add the rest in the body, like (for [i 0 3] (let [k (+ i 1000)] ...))"))))
      (let [i (fresh! st "i")
            v (fresh! st "v")
            sc (new-scope st.scope)
            saved-weight st.weight
            saved-scope st.scope]
        (count-local! st node 1)
        (bind! sc name {:kind :value :fn st.fn
                        :part {:g v :l v :t :float
                               :range (when (> turns 0) [(math.min start last) (math.max start last)])}})
        (set st.weight (* st.weight (math.max turns 1)))
        (set st.scope sc)
        (let [(block) (capture st
                               (fn []
                                 ;; Fennel's loop stops before a turn past its stop, then
                                 ;; tests &until at the top of each turn.
                                 (when cap-value
                                   (emit! st (.. "if (" v (if (> step 0) " > " " < ") cap-value.g ") break;")
                                          (.. "if " v (if (> step 0) " > " " < ") cap-value.l " then break end")))
                                 (when until-node
                                   (let [(cblock c) (capture st #(bool-arg st until-node))]
                                     (cost! st until-node 1)
                                     (each [_ item (ipairs cblock)] (table.insert st.out item))
                                     (emit! st (.. "if (" c.g ") break;") (.. "if " c.l " then break end"))))
                                 (body st sc (fcollect [k 3 (length node)] (. node k)) node)))]
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
  ;; translated as a helper at each call with new kinds of arguments, its own outside
  ;; names looked up by its `resolve`.
  (when (not (. st.external form))
    (tset st.external form (helper-binding st (new-scope nil) form name resolve)))
  (. st.external form))

(fn scope-helpers [st]
  "The names of the helpers in reach, for a guess at a misspelt one."
  (let [out []]
    (var sc st.scope)
    (while sc
      (each [name b (each-pair sc.names)]
        (when (= b.kind :helper) (table.insert out name)))
      (set sc sc.parent))
    (table.sort out)
    out))

(fn finite [n]
  ;; math.huge from outside the function (a (local {: huge} math)) is the huge of
  ;; math.huge itself; any other infinity or a nan is refused by `constant`.
  (if (= n math.huge) huge (= n (- math.huge)) (- huge) n))

(fn table-part [st node name t]
  ;; A table of the file: an array of numbers, or of vectors of 2 or 3 numbers, as
  ;; constants (a vector when it is 2 or 3 numbers).
  (let [n (length t)
        keys (accumulate [k 0 _ (each-pair t)] (+ k 1))
        bad #(refuse st node (.. "`" name "` is a table that is not an array of numbers or of vectors [a b] or [a b c]"
                                 (if $ (.. " (" $ ")") "")
                                 "; a distance function may use numbers, math functions, functions of the file and such arrays from outside it"))
        number (fn [x] (if (= (type x) :number) (constant st node (finite x)) (bad "an item is not a number")))]
    (when (or (= n 0) (not= keys n)) (bad (if (= n 0) "it has no items 1, 2, ..." "it has keys besides 1 to n")))
    (when (> n limits.array-items) (bad (.. n " items; at most " limits.array-items)))
    (let [items (fcollect [i 1 n]
                  (let [x (. t i)]
                    (if (= (type x) :table)
                        (let [m (length x)]
                          (when (or (not (<= 2 m 3)) (not= m (accumulate [k 0 _ (each-pair x)] (+ k 1))))
                            (bad "a vector item must be [a b] or [a b c]"))
                          {:t :vec :comps (fcollect [j 1 m] (number (. x j)))})
                        (number x))))
          sizes (collect [_ p (ipairs items)] (if (= p.t :vec) (length p.comps) 0) true)]
      (when (not= 1 (accumulate [k 0 _ (each-pair sizes)] (+ k 1)))
        (bad "its items are not all numbers or all vectors of one size"))
      (if (and (<= 2 n 3) (= :float (. items 1 :t))) {:t :vec :comps items}
          {:t :array : items}))))

(fn may-use [name]
  ;; The list of math's names a distance function may use, but after an alias's hint,
  ;; which says what to write (and a message stays short enough to be shown whole).
  (if (. aliases (or (name:match "^math%.(.+)$") name)) ""
      (.. " (it may use " math-list ")")))

(fn resolve-free [st node name ?call]
  "The binding of `name`, which is not bound in the function: math's (math.x), or
what the scene's resolver says of a name from outside the function. `?call`: the
name is called, and a refusal lists what may be called."
  (let [field (name:match "^math%.([%w_]+)$")]
    (if (and field (. math-constants field)) {:kind :value :part (constant st node (. math-constants field))}
        (and field (. math-functions field)) {:kind :math :name field}
        field (refuse st node (.. "`" name "` is not one of the math functions a distance function may use"
                                  (suggestion name) (may-use name)))
        (case (and st.resolve (st.resolve name))
          {:number n} {:kind :value :part (constant st node (finite n))}
          {:math f} (if (. math-functions f) {:kind :math :name f}
                        (refuse st node (.. "`" name "` is math." f ", which a distance function cannot use"
                                            (suggestion f) (may-use f))))
          ;; (local {: clamp} math): Lua's math has no clamp, so the name holds nil
          ;; when the file runs; the translation has GLSL's.
          {:nil true} (if (or (?. math-functions name :library) (?. math-functions name :vector)) {:kind :math :name name}
                          (refuse st node (.. "`" name "` is nil from outside the function; a name from outside it may hold a number, a math function or a function of the file"
                                              (suggestion name (scope-helpers st)))))
          {:unreadable why} (refuse st node (.. "`" name "` is a function the translator cannot read: " why
                                                (if (?. math-functions name :library)
                                                    (.. "; or call math." name ", GLSL's " name)
                                                    (suggestion name))))
          {:helper form :resolve resolve} (external-helper st node name form resolve)
          {:table t} {:kind :value :part (table-part st node name t)}
          {:other what} (refuse st node (.. "`" name "` is " what " from outside the function; a distance function may use numbers and math functions from outside it"))
          _ (if ?call
                (refuse st node (.. "`" name "` is not a function a distance function may call"
                                    (suggestion name (scope-helpers st))
                                    " (it may call " math-call-list ", and helper functions: (fn name [a b] ...) in the function or the file)"))
                (refuse st node (.. "`" name "` is not defined in the distance function (it may use its arguments, its own locals and helpers, math.*, and numbers or math functions named outside it)")))))))

(fn symbol [st node]
  (let [name (tostring node)]
    (when (= name "nil") (refuse st node "`nil` is not a number"))
    ;; v.x is Fennel's field "x" of the table v: nil for a vector [x y z].
    (case (name:match "^([^.]+)%.([xyzw])$")
      (base field) (when (?. (lookup st.scope base) :part :comps)
                     (refuse st node (.. "`" name "` is the field \"" field "\" of a table, nil for a vector [a b c] in Fennel; take its component: (. " base " "
                                         (. {:x 1 :y 2 :z 3 :w 4} field) ")"))))
    (case (or (lookup st.scope name) (resolve-free st node name))
      {:kind :value : part} (do (when (and (not (constant-value? part)) (not= (?. (lookup st.scope name) :fn) st.fn))
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
          "." (index-form st node)
          "length" (length-form st node)
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
                         (fennel.sequence? node) (sequence-form st node)
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
                    (let [name (check-name! st (. form 2))]
                      (bind! sc name (helper-binding st sc form name))
                      [])
                    (and (fennel.list? form) (= "local" (sym-name (. form 1))))
                    (local-form st form sc false)
                    (and (fennel.list? form) (= "var" (sym-name (. form 1))))
                    (local-form st form sc true)
                    (expr st form))))
         (when (= 0 (length forms)) (refuse st at "an empty body gives no value"))
         (set st.scope saved)
         parts)))

(fn params-of [st node ?patterns]
  "The fn form `node`'s name symbol (or nil), parameter names (with `?patterns`, the
parameters as written: names or [...] patterns) and body forms."
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
              (icollect [_ p (ipairs params)] (if (and ?patterns (fennel.sequence? p)) p (check-name! st p)))
              (fcollect [i first (length node)] (. node i))))))

(fn new-fn [st]
  (set st.fn-count (+ st.fn-count 1))
  {:id st.fn-count :locals 0})

(fn snapshot [sc]
  ;; The names in reach at `sc`, in a scope of their own: a helper translated at its
  ;; first call sees what it saw where it was written, not names bound after it.
  (let [names {}]
    (var s sc)
    (while s
      (each [k v (each-pair s.names)] (when (= nil (. names k)) (tset names k v)))
      (set s s.parent))
    {: names}))

(set helper-binding
     (fn [st sc node label ?resolve]
       "The binding of the helper function `node`, written where `sc` is in reach:
translated at each call with a new kind of arguments (see instance)."
       (let [(_ params) (params-of st node true)]
         {:kind :helper :form node :scope (snapshot sc) :label label :nargs (length params)
          :resolve (or ?resolve st.resolve) :instances {}})))

(fn define-helper [st sc node args]
  ;; The GLSL and Lua function of the helper `node` for argument values like `args`
  ;; (numbers and vectors), in scope `sc`: its helper record.
  (when (>= (length st.helpers) limits.helpers)
    (refuse st node (.. "more than " limits.helpers " helper functions")))
  (let [(name-sym patterns forms) (params-of st node true)
        ;; Named after the function: two custom functions in one shader each
        ;; have their own helpers.
        name (.. st.name "Fn" (length st.helpers))
        _ (table.insert st.helpers false)   ; its place, for the next helper's name
        slot (length st.helpers)
        saved {:fn st.fn :scope st.scope :weight st.weight :cost st.cost :out st.out :line st.line}
        fsc (new-scope sc)]
    (set st.fn (new-fn st))
    (set st.weight 1)
    (set st.cost 0)
    (when name-sym (bind! fsc (tostring name-sym) {:kind :recursive}))
    (let [fresh (fn [] (let [v (fresh! st "v")] {:g v :l v :t :float}))
          params (icollect [i pattern (ipairs patterns)]
                   (let [a (. args i)
                         p (if (= a.t :vec) {:t :vec :comps (fcollect [_ 1 (length a.comps)] (fresh))} (fresh))]
                     (bind-part! st fsc pattern p node true)
                     p))
          (names) (flat st node params)
          _ (count-local! st node (length names))
          (block parts) (capture st #(check-parts st node (body st fsc forms node)))
          (numbers shape) (flat st node parts)
          nret (length numbers)]
      (when (or (= nret 0) (accumulate [b? false _ p (ipairs numbers)] (or b? (= p.t :bool))))
        (refuse st node "a helper function must return numbers or vectors, one to four numbers in all"))
      (let [helper {: name :nargs (length names) : nret : shape :cost st.cost}
            gargs (table.concat (icollect [_ a (ipairs names)] (.. "float " a.g)) ", ")
            gret (if (= nret 1) (. numbers 1 :g)
                     (.. (vec-type nret) "(" (table.concat (icollect [_ p (ipairs numbers)] p.g) ", ") ")"))]
        (table.insert block {:g (.. "return " gret ";")
                             :l (.. "return " (table.concat (icollect [_ p (ipairs numbers)] p.l) ", "))})
        (tset st.helpers slot
              {: helper
               :item {:g (.. (vec-type nret) " " name "(" gargs ") {")
                      :l (.. "local function " name "(" (table.concat (icollect [_ a (ipairs names)] a.l) ", ") ")")
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
        (set st.line saved.line)
        helper))))

(set instance
     (fn [st node b args]
       "The translation of helper binding `b` for arguments like `args`: the one made
at an earlier call with the same kinds (numbers, vectors of a size), else a new one."
       (let [kinds (table.concat (icollect [_ a (ipairs args)] (if (= a.t :vec) (.. "vec" (length a.comps)) "float")) " ")]
         (or (. b.instances kinds)
             (do (when b.busy
                   (refuse st node (.. "`" b.label "` calls itself: recursion is not supported in a distance function")))
                 (set b.busy true)
                 (let [saved st.resolve
                       _ (set st.resolve b.resolve)
                       helper (define-helper st b.scope b.form args)]
                   (set st.resolve saved)
                   (set b.busy false)
                   (tset b.instances kinds helper)
                   helper))))))

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
scene file, or (fn [p] ...), the point as one vector. Returns {:glsl :lua :params [name ...] :cost n}: :glsl defines
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
           (let [(name-sym names forms) (params-of st form true)
                 ;; (fn [p] ...): the point as one vector.
                 point? (= 1 (length names))
                 _ (when (and (not point?) (< (length names) 3))
                     (refuse st form (.. "a distance function takes the point first: (fn [x y z] ...), or as one vector (fn [p] ...)"
                                         (if (= 2 (length names))
                                             "; with parameters after a vector point, write (fn [x y z r] (let [p [x y z]] ...))"
                                             ""))))
                 _ (when (not point?) (each [_ n (ipairs names)] (when (not= (type n) :string) (check-name! st n))))
                 sc (new-scope nil)
                 main-fn (new-fn st)
                 _ (set st.fn main-fn)
                 vars (fcollect [_ 1 (if point? 3 (length names))] (fresh! st "v"))
                 scale (when (not= false options.scale?) (fresh! st "v"))]
             (count-local! st form (length vars))
             (when name-sym (bind! sc (tostring name-sym) {:kind :recursive}))
             (if point?
                 (bind-part! st sc (. names 1) {:t :vec :comps (icollect [_ v (ipairs vars)] {:g v :l v :t :float})}
                             form true)
                 (each [i n (ipairs names)]
                   (when (not= n "_")
                     (bind! sc n {:kind :value :fn main-fn :part {:g (. vars i) :l (. vars i) :t :float}}))))
             (let [(block parts) (capture st #(body st sc forms form))
                   _ (when (not= 1 (length parts))
                       (refuse st form (.. "a distance function must give one number, this one gives "
                                           (length parts) " values")))
                   d (. parts 1)
                   _ (when (not= d.t :float)
                       (refuse st form (if (= d.t :bool) "a distance function must give a number, not a comparison"
                                           (.. "a distance function must give a number, not " (describe d)
                                               "; take (length v) or a component (. v 1)"))))
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
                 (let [size (accumulate [n 0 _ l (ipairs glsl)] (+ n (length l) 1))]
                   (when (> size limits.text)
                     (refuse st form (string.format "its translation is %d KB of GLSL, more than %d KB; the shader would take long to compile: write the function shorter (a value used in several places bound once with let)"
                                                    (math.ceil (/ size 1024)) (/ limits.text 1024)))))
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

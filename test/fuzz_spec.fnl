;; tier: fast
;; Seeded fuzzing of the scene loader: the valid scenes in scenes/ are mutated as text
;; (characters and tokens deleted, inserted, duplicated and swapped, numbers replaced by
;; NaN, infinities and huge values, keywords swapped between scenes, brackets dropped,
;; fragments of other scenes spliced in...) and every mutant goes through
;; scene.load-string and, when it loads, plan.scene->plan. Each outcome must be a table,
;; or nil and a non-empty message starting with the file name: never an error.
;; FUZZ_SEED=n picks another seed; the seed is printed either way. The number of cases
;; is fixed, 10,000 or FUZZ_CASES=n (`make check` runs 500: the first 500 of the same
;; sequence), never a time budget: the verdict must not depend on the machine's speed; each
;; case is bounded by the loader's own step and memory limits. One mutation in twenty
;; inserts a hostile fragment (compile-time code in key position, huge strings, bytes
;; that are not UTF-8, holes in vectors, ...), and every message must be safe to print.
(local scene (require :src.scene.load))
(local emit-lua (require :src.sdf.emit-lua))
(local codegen (require :src.render.codegen))
(local plan (require :src.render.plan))
(local text (require :src.util.text))

(local default-seed 20250611)
(local cases (or (tonumber (os.getenv "FUZZ_CASES")) 10000))
(local max-reported 5)

;;; A small deterministic generator (Park-Miller), independent of math.random.

(fn make-rng [seed]
  (var state (+ 1 (% (math.abs (math.floor seed)) 2147483646)))
  (fn [n]
    "An integer from 1 to n."
    (set state (% (* state 16807) 2147483647))
    (+ 1 (% state n))))

(fn pick [rng list] (. list (rng (length list))))

;;; Tokens of a scene's text: strings, brackets and atoms, with their byte positions.

(fn tokenize [src]
  (let [tokens []
        n (length src)]
    (var i (src:find "[^%s]"))
    (while i
      (let [c (src:sub i i)
            e (if (= c ";") (or (src:find "\n" i true) n)
                  (= c "\"") (or (src:find "\"" (+ i 1) true) n)
                  (c:find "[%(%)%[%]{}]") i
                  (- (or (src:find "[%s%(%)%[%]{}\";]" i) (+ n 1)) 1))]
        (when (not= c ";")
          (table.insert tokens {:s i :e e :text (src:sub i e)}))
        (set i (src:find "[^%s]" (+ e 1)))))
    tokens))

(fn number-token? [t]
  (and (not= (t.text:sub 1 1) ":") (not= (tonumber t.text) nil)))

(fn keyword-token? [t]
  (and (= (t.text:sub 1 1) ":") (> (length t.text) 1)))

(fn closing-token? [t] (not= (t.text:find "^[%)%]}]$") nil))

(fn replace-span [src s e text]
  (.. (src:sub 1 (- s 1)) text (src:sub (+ e 1))))

(fn tokens-where [src ok?]
  (icollect [_ t (ipairs (tokenize src))] (when (ok? t) t)))

;;; Mutations: each takes the source, the generator and the other scenes' texts.

(local odd-numbers ["(/ 0 0)" "(/ 1 0)" "(/ -1 0)" "(- (/ 0 0))" "-1" "0" "-0" "1e308"
                    "-1e308" "1e400" "1e-320" "9007199254740993" "9223372036854775808"
                    "-2147483649" "0x7fffffff" "1.5" "100001" "17" "\"1\"" "true" "nil"
                    "[]" "{}" "[1 2]" "math.huge" "(- math.huge)"])

(local odd-snippets ["(" ")" "[" "]" "{" "}" "\"" ":" "#" "~" "@" "`" "," "\\" ";" "\n"
                     "nil" "(/ 0 0)" "[]" "{}" "\"\"" ":kind" ":objects" "(fn [] 1)"
                     "..." "&" "(. nil 1)" "(string.rep \"x\" 10)" "#[]" "$" "x" "0" "-"
                     "(do)" "(values)" "(length nil)" "{:kind :sphere}" "{1 2}" "1e999"
                     ;; Tree nodes: empty, odd and unbounded children, deep wrappers.
                     "{:kind :union :children []}" "{:kind :twist :children [{:kind :plane}]}"
                     ":children" "[{:kind :sphere} {:kind :box}]" "{:kind :repeat :period [0 0 0]}"
                     "{:kind :smooth-union :radius 0 :children [{:kind :sphere} 1]}"
                     "{:kind :round :children [{:kind :round :children [{:kind :round}]}]}"])

(local extra-keywords [":kind" ":sphere" ":box" ":plane" ":torus" ":pos" ":radius" ":size"
                       ":color" ":height" ":objects" ":camera" ":light" ":render"
                       ":environment" ":name" ":yaw" ":pitch" ":fov" ":max-steps"
                       ":epsilon" ":draw-distance" ":reflections" ":shadows" ":glow"
                       ":scale" ":radus" ":" ":1" ":nil"
                       ;; Scene trees.
                       ":children" ":union" ":subtraction" ":smooth-union" ":twist" ":bend"
                       ":repeat" ":polar" ":period" ":count" ":kernel" ":exp" ":mirror"
                       ":rotate" ":axis" ":angle" ":normal" ":thickness" ":onion" ":displace"])

(fn random-span [rng src max-len]
  (let [n (length src)
        s (rng (math.max n 1))
        len (rng max-len)]
    (values s (math.min n (+ s len -1)))))

(fn replace-number [src rng]
  (let [ts (tokens-where src number-token?)]
    (if (= (length ts) 0) src
        (let [t (pick rng ts)] (replace-span src t.s t.e (pick rng odd-numbers))))))

(fn swap-keyword [src rng others]
  (let [ts (tokens-where src keyword-token?)
        pool (tokens-where (pick rng others) keyword-token?)]
    (if (= (length ts) 0) src
        (let [t (pick rng ts)
              new (if (or (= (rng 2) 1) (= (length pool) 0)) (pick rng extra-keywords)
                      (. (pick rng pool) :text))]
          (replace-span src t.s t.e new)))))

;; Mutations of either list below (see gentle-mutations).

(local mutations
  [;; characters
   (fn delete-char [src rng]
     (if (= (length src) 0) src (let [i (rng (length src))] (replace-span src i i ""))))
   (fn insert-char [src rng]
     (let [i (rng (+ (length src) 1))
           c (if (= (rng 3) 1) (string.char (rng 255)) (pick rng odd-snippets))]
       (replace-span src i (- i 1) c)))
   (fn duplicate-span [src rng]
     (let [(s e) (random-span rng src 40)] (replace-span src s (- s 1) (src:sub s e))))
   (fn swap-chars [src rng]
     (let [n (length src)]
       (if (< n 2) src
           (let [a (rng n) b (rng n) lo (math.min a b) hi (math.max a b)]
             (if (= lo hi) src
                 (.. (src:sub 1 (- lo 1)) (src:sub hi hi) (src:sub (+ lo 1) (- hi 1))
                     (src:sub lo lo) (src:sub (+ hi 1))))))))
   (fn truncate [src rng] (src:sub 1 (- (rng (+ (length src) 1)) 1)))
   ;; tokens
   (fn delete-token [src rng]
     (let [ts (tokenize src)]
       (if (= (length ts) 0) src (let [t (pick rng ts)] (replace-span src t.s t.e "")))))
   (fn duplicate-token [src rng]
     (let [ts (tokenize src)]
       (if (= (length ts) 0) src
           (let [t (pick rng ts)] (replace-span src t.s t.e (.. t.text " " t.text))))))
   (fn swap-tokens [src rng]
     (let [ts (tokenize src)]
       (if (< (length ts) 2) src
           (let [a (pick rng ts) b (pick rng ts)
                 [x y] (if (< a.s b.s) [a b] [b a])]
             (if (= x y) src
                 (.. (src:sub 1 (- x.s 1)) y.text (src:sub (+ x.e 1) (- y.s 1)) x.text
                     (src:sub (+ y.e 1))))))))
   ;; a number replaced twice as often as each other mutation
   replace-number
   replace-number
   swap-keyword
   (fn drop-closing [src rng]
     (let [ts (tokens-where src closing-token?)]
       (if (= (length ts) 0) src (let [t (pick rng ts)] (replace-span src t.s t.e "")))))
   (fn extra-closing [src rng]
     (let [i (rng (+ (length src) 1))] (replace-span src i (- i 1) (pick rng [")" "]" "}"]))))
   (fn splice-other [src rng others]
     (let [other (pick rng others)
           (s e) (random-span rng other 120)
           i (rng (+ (length src) 1))]
       (replace-span src i (- i 1) (other:sub s e))))
   (fn replace-with-other-token [src rng others]
     (let [ts (tokenize src)
           pool (tokenize (pick rng others))]
       (if (or (= (length ts) 0) (= (length pool) 0)) src
           (let [t (pick rng ts)] (replace-span src t.s t.e (. (pick rng pool) :text))))))])

(fn atom-token? [t] (= (t.text:find "^[%(%)%[%]{}]$") nil))

(local gentle-mutations
  ;; Keep the brackets balanced, so the mutant usually parses and reaches validation.
  [replace-number
   swap-keyword
   (fn delete-atom [src rng]
     (let [ts (tokens-where src atom-token?)]
       (if (= (length ts) 0) src (let [t (pick rng ts)] (replace-span src t.s t.e "")))))
   (fn duplicate-atom [src rng]
     (let [ts (tokens-where src atom-token?)]
       (if (= (length ts) 0) src
           (let [t (pick rng ts)] (replace-span src t.s t.e (.. t.text " " t.text))))))
   (fn other-scene-atom [src rng others]
     (let [ts (tokens-where src atom-token?)
           pool (tokens-where (pick rng others) atom-token?)]
       (if (or (= (length ts) 0) (= (length pool) 0)) src
           (let [t (pick rng ts)] (replace-span src t.s t.e (. (pick rng pool) :text))))))
   (fn swap-atoms [src rng]
     (let [ts (tokens-where src atom-token?)]
       (if (< (length ts) 2) src
           (let [a (pick rng ts) b (pick rng ts)
                 [x y] (if (< a.s b.s) [a b] [b a])]
             (if (= x y) src
                 (.. (src:sub 1 (- x.s 1)) y.text (src:sub (+ x.e 1) (- y.s 1)) x.text
                     (src:sub (+ y.e 1))))))))])

(local hostile-fragments
  ["{(eval-compiler (while true nil)) 1}" "{(macro m [] 1) 2}" "{(lua \"os.exit()\") 1}"
   "(do (eval-compiler (tset _SPECIALS :local nil)) :environment)"
   "{(include :x) 1}" "{(import-macros m :x) 1}" "(global x 1)" "[nil nil 5]" "[nil 1 1]"
   "(string.rep \"x\" 1000000)" "(table.concat (fcollect [i 1 2000] (string.rep \"x\" 999999)))"
   "(string.format (string.rep \"%s\" 40) (string.rep \"y\" 999999))"
   "(string.rep \"\\27[2J\" 100)" "\255\254" "\239\187\191" "\000" "\192\128"
   "1e308" "-1e308" "1e-300" "(/ 0 0)" "((fn f [] (f)))" "(while true)"
   "{:kind (string.rep \"k\" 100000)}" ":name (string.rep \"n\" 100000)"])

(fn insert-hostile [src rng]
  (let [i (rng (+ (length src) 1))]
    (replace-span src i (- i 1) (.. " " (pick rng hostile-fragments) " "))))

(fn mutate [src rng others]
  "One to three mutations (sometimes four to nine): gentle ones four times in five,
a hostile fragment one time in twenty."
  (var out src)
  (let [rounds (if (= (rng 10) 1) (+ 3 (rng 6)) (rng 3))]
    (for [_ 1 rounds]
      (if (= (rng 20) 1) (set out (insert-hostile out rng))
          (let [pool (if (<= (rng 5) 4) gentle-mutations mutations)]
            (set out ((pick rng pool) out rng others))))))
  out)

;;; The property

(fn outcome-problem [file ok? a b]
  "nil when the outcome of loading (pcall'd) is acceptable, else what is wrong."
  (if (not ok?) (.. "uncaught error: " (tostring a))
      (= (type a) :table) nil
      (not= a nil) (.. "returned " (type a) " " (tostring a) " instead of a table or nil")
      (not= (type b) :string) (.. "nil without a message (got " (type b) ")")
      (= b "") "an empty message"
      (not= (b:sub 1 (length file)) file) (.. "a message not starting with the file name: " b)
      (> (length b) 600) (.. "a message of " (length b) " bytes")
      (not (text.valid-utf8? b)) "a message that is not UTF-8 text"
      (b:find "[%c]") "a message with a control character (a terminal escape?)"
      nil))

(fn message-kind [file msg]
  (let [rest (msg:sub (+ (length file) 1))]
    (if (rest:find "Parse error" 1 true) :parse
        (rest:find "Compile error" 1 true) :compile
        (rest:find "is not allowed" 1 true) :compile-time-form
        (rest:find "^:%d+: [%w%.%[%]%-]+: ") :field
        (rest:find "^: objects: the scene needs") :budget
        (rest:find "^: the scene") :limit
        :runtime)))

(fn load-and-plan [src file]
  ;; A scene that loads must also lower, emit its CPU evaluator and its shader.
  (let [(s err) (scene.load-string src file)]
    (if s
        (case (plan.scene->plan s)
          p (do (when p.tape (emit-lua.compile p.tape))
                (assert (codegen.shader p :core))
                p)
          (nil perr) (values nil perr))
        (values nil err))))

(fn read-file [path]
  (with-open [f (assert (io.open path :rb))] (f:read :*a)))

(fn run-cases [rng paths texts stats]
  "Make and check `cases` mutants; fills `stats`."
  (let [start (os.clock)]
    (while (< stats.n cases)
      (set stats.n (+ stats.n 1))
      (let [k (rng (length texts))
            file (. paths k)
            src (mutate (. texts k) rng texts)
            t0 (os.clock)
            (ok? a b) (pcall load-and-plan src file)
            dt (- (os.clock) t0)
            problem (outcome-problem file ok? a b)]
        (when (> dt stats.slowest)
          (set stats.slowest dt)
          (set stats.slowest-src src))
        (if problem
            (table.insert stats.failures {:case stats.n : file : src : problem})
            (= (type a) :table)
            (set stats.loaded (+ stats.loaded 1))
            (let [kind (message-kind file b)]
              (set stats.refused (+ stats.refused 1))
              (tset stats.kinds kind (+ 1 (or (. stats.kinds kind) 0)))))))
    (set stats.elapsed (- (os.clock) start))))

(describe "fuzzing the scene loader with mutated scenes"
  (fn []
    (it (.. "survives " cases " mutants of scenes/*.fnl")
      (fn []
        (let [seed (or (tonumber (os.getenv "FUZZ_SEED")) default-seed)
              rng (make-rng seed)
              paths (with-open [p (io.popen "ls -1 scenes/*.fnl")]
                      (icollect [line (p:lines)] line))
              texts (icollect [_ path (ipairs paths)] (read-file path))
              stats {:n 0 :loaded 0 :refused 0 :warnings 0 :kinds {} :failures []
                     :slowest 0 :elapsed 0}
              ;; Fennel writes parse warnings ('--WARNING: ... expected whitespace') to
              ;; io.stderr: count them instead of flooding the test output.
              real-stderr io.stderr
              stderr-stub {:write (fn [self] (set stats.warnings (+ stats.warnings 1)) self)}]
          (print (.. "\nfuzz seed " seed " (FUZZ_SEED=" seed " to replay), "
                     (length paths) " scenes"))
          (assert.is_true (> (length texts) 0) "no scenes in scenes/")
          ;; The unmutated scenes load: the property is not vacuous.
          (each [i text (ipairs texts)]
            (assert.are.equal :table (type (load-and-plan text (. paths i))) (. paths i)))
          (set io.stderr stderr-stub)
          (let [(ok? err) (pcall run-cases rng paths texts stats)]
            (set io.stderr real-stderr)
            (when (not ok?) (error err 0)))
          (print (string.format (.. "fuzz: %d cases in %.1f s (%d loaded, %d refused, %d failed);"
                                    " slowest case %.2f s")
                                stats.n stats.elapsed stats.loaded stats.refused
                                (length stats.failures) stats.slowest))
          (print (.. "fuzz: refusals by kind: "
                     (table.concat (doto (icollect [k v (pairs stats.kinds)] (.. k " " v))
                                     table.sort) ", ")
                     "; " stats.warnings " Fennel warnings written to stderr (hidden)"))
          (when (> stats.slowest 0.5)
            (print (.. "fuzz: the slowest mutant:\n" stats.slowest-src)))
          (each [i f (ipairs stats.failures) &until (> i max-reported)]
            (print (string.format "\nfuzz failure %d/%d, case %d of %s: %s\n--- mutated source ---\n%s\n---"
                                  i (length stats.failures) f.case f.file f.problem f.src)))
          (assert.are.equal cases stats.n)
          (assert.are.equal 0 (length stats.failures)
                            (.. (length stats.failures) " mutants gave a bad outcome; first: "
                                (if (. stats.failures 1) (. stats.failures 1 :problem) ""))))))))

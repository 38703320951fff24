;; Running a scene file's code safely: checks on the text before it is parsed (size,
;; encoding, nesting), an allowlist of the forms a data file may use (compile-time
;; code never runs), the only globals the code sees, and step and memory limits while
;; it runs. Whatever a scene does ends with its own load.

(local fennel (require :fennel))
(local text (require :src.util.text))
;; `pairs` under another name: a loop over `pairs` by that name is LuaJIT's ITERN,
;; which Debian 12's LuaJIT ends early once despecialised (see src/util/wire.fnl).
(local each-pair pairs)

(local limits
  {:file-bytes (* 512 1024)       ; a scene file: about 6500 spheres written out, 2 s
                                  ; to parse and compile (10,000 take 780 KB and 3 s,
                                  ; so it stays); larger scenes come from a loop, and
                                  ; 100,000 spheres made by one load in 0.6 s
   ;; A file of plain data (src/scene/data.fnl) is read without the compiler, at
   ;; about 50 MB/s here: 360,000 spheres written out take 31 MB, 0.55 s to read
   ;; (1.2 s with the checks) and 153 MB as tables (100,000: 8.7 MB, 0.17 s, 39 MB).
   ;; Denser text makes more tables a byte (`[] [] ...`, one every 3 bytes): the
   ;; memory they take is checked as they are made, and 33 MB of that is refused
   ;; after 1 s at 466 MB resident.
   :data-bytes (* 32 1024 1024)
   :data-memory-mb 256
   :nesting 100                   ; brackets inside brackets (a tree 32 nodes deep takes 66)
   :steps 20000000                ; Lua VM instructions before the scene has built
                                  ; anything (an endless loop: about 0.4 s here) ...
   :steps-per-kb 500              ; ... and this many more per KB of memory it has
                                  ; reached. A sphere made by a loop keeps about
                                  ; 340 bytes and takes 74 to 127 steps (99 in
                                  ; test/fixtures/spheres-100000.fnl): 170 allowed.
                                  ; The most any scene gets: 20 + 500 x 524,288 KB =
                                  ; 282 million steps (about 6 s here)
   :memory-mb 512                 ; Lua memory the scene may build, garbage included:
                                  ; 1,000,000 spheres made by a loop keep 342 MB
   :string-bytes (* 1024 1024)    ; one string made by a library call
   :cpu-seconds 5                 ; a backstop while a scene runs: the step limit
                                  ; trips long before (it grows as the steps do)
   ;; Compiling (the compiler is Lua code too; a macro can copy its arguments
   ;; without end: nested case-try, 4 KB, took 1.3 GB and more). Every instruction
   ;; of a compile is counted (the JIT's traces are flushed for it, see
   ;; within-limits): a 512 KB file of 6000 spheres written out compiles in 86
   ;; million steps (1.0 s) and 43 MB at the peak; the scenes in scenes/ take 0.25
   ;; to 0.36 million; a loop of 100,000 objects is a short file. 512 KB of dense
   ;; macros (case, match-try, icollect on every line) took 259 MB, and is refused.
   :compile-steps 200000000       ; about 2.3 s here
   :compile-memory-mb 128         ; Lua memory, garbage included
   ;; A backstop for time the step count does not see (long library calls). The
   ;; steps must trip first on a slow or busy machine too: the 200 million take
   ;; 2.3 s of CPU here, and at 5 s a compile stopped by its steps on a busy
   ;; 2-core CI machine said "took more than 5 s" instead. 15 s: six times the
   ;; steps' time, and under the worker's 20 s of CPU a load, so the message still
   ;; names the compile.
   :compile-cpu-seconds 15
   :compile-hook-every 1000       ; instructions between the compiler's limit checks
   :hook-every 4})                ; instructions between limit checks

;; Our own errors carry this table, which no scene can reach, so a scene cannot forge
;; one by raising a table of the same shape.
(local marker {})

(fn stop [message]
  (error {:sandbox marker : message} 0))

(fn sandbox-error? [e]
  (and (= (type e) :table) (rawequal (rawget e :sandbox) marker)))

;;; The text, before parsing

(fn line-of [source pos]
  (let [(_ n) (: (source:sub 1 (- pos 1)) :gsub "\n" "")] (+ n 1)))

(fn check-encoding [source file]
  "A message when `source` is not UTF-8 text (or holds NUL bytes), else nil."
  ;; Plain ASCII without NUL, the usual scene, is settled by one search.
  (case (and (source:find "[\128-\255%z]") (text.first-invalid-byte source))
    pos (let [line (line-of source pos)
              line-start (or (: (source:sub 1 pos) :match ".*\n()") 1)]
          (string.format "%s:%d: the file is not UTF-8 text (byte 0x%02X at column %d); scene files are Fennel source"
                         file line (source:byte pos) (+ 1 (- pos line-start))))))

(fn nesting-depth [source]
  "The deepest bracket nesting of `source` and the line where it is first reached,
skipping strings and comments: measured on the text, so it also holds for input the
parser would recurse on until the stack overflows."
  (var depth 0)
  (var deepest 0)
  (var deepest-line 1)
  (var line 1)
  (var i 1)
  (let [n (length source)]
    (while (<= i n)
      (let [c (source:byte i)]
        (if (= c 10) (set line (+ line 1))
            (= c 59) (let [e (source:find "\n" i true)] ; ; comment
                       (set i (- (or e (+ n 1)) 1)))
            (= c 34) (do (set i (+ i 1))                ; " string
                         (while (and (<= i n) (not= (source:byte i) 34))
                           (case (source:byte i)
                             92 (set i (+ i 1))
                             10 (set line (+ line 1)))
                           (set i (+ i 1))))
            (or (= c 40) (= c 91) (= c 123))
            (do (set depth (+ depth 1))
                (when (> depth deepest) (set deepest depth) (set deepest-line line)))
            (or (= c 41) (= c 93) (= c 125)) (set depth (math.max 0 (- depth 1))))
        (set i (+ i 1)))))
  (values deepest deepest-line))

(fn nesting-line [source]
  "The line where `source` first reaches its deepest nesting."
  (let [(_ line) (nesting-depth source)] line))

(fn nesting-message [file line]
  (.. file (if line (.. ":" line) "") ": the scene nests deeper than " limits.nesting
      " levels of brackets"))

(fn check-source [source file]
  "The text of a scene ready to parse (a UTF-8 byte order mark dropped), or nil and a
message when it is too large, not UTF-8 text or nested too deeply."
  (let [source (if (= (source:sub 1 3) "\239\187\191") (source:sub 4) source)]
    (if (> (length source) limits.file-bytes)
        (values nil (string.format "%s: the file is over %d bytes (512 KB), the most a scene file may have; make many objects with a loop, like (fcollect [i 1 n] {:kind :sphere ...})"
                                   file limits.file-bytes))
        (case (check-encoding source file)
          msg (values nil msg)
          _ (let [(depth line) (nesting-depth source)]
              (if (> depth limits.nesting) (values nil (nesting-message file line))
                  source))))))

;;; The parsed forms: an allowlist

;; The special forms and built-in macros a data file may use. Every other special
;; form or macro the compiler knows (eval-compiler, macro, lua, include, global,
;; import-macros, quote, ..., and any added in a later Fennel) is refused, wherever it
;; stands: a value, a key, a binding.
(local allowed-forms
  (collect [_ name (ipairs ["#" "%" "*" "+" "-" "." ".." "/" "//" ":" "<" "<=" "=" ">"
                            ">=" "^" "and" "band" "bnot" "bor" "bxor" "comment" "do" "each"
                            "fn" "for" "hashfn" "if" "length" "let" "local" "lshift" "not"
                            "not=" "or" "pick-values" "rshift" "set" "tail!" "tset" "values"
                            "var" "while" "~=" "->" "->>" "-?>" "-?>>" "?." "accumulate"
                            "case" "case-try" "collect" "doto" "faccumulate" "fcollect"
                            "icollect" "lambda" "λ" "match" "match-try" "partial" "when"])]
    name true))

(fn global-scope []
  (let [scope (fennel.scope)]
    (or scope.parent scope)))

(fn compile-time-form? [name]
  "True when `name` is a special form or macro that is not on the allowlist."
  (let [g (global-scope)]
    (and (not (. allowed-forms name))
         (or (not= nil (. g.specials name)) (not= nil (. g.macros name))))))

(fn find-forbidden [node depth]
  "The first refused form inside `node` (keys and values alike), or :too-deep."
  (if (> depth limits.nesting) :too-deep
      (or (not= (type node) :table) (fennel.sym? node)) nil
      (let [head (and (fennel.list? node) (. node 1))
            name (and head (fennel.sym? head) (tostring head))]
        (if (and name (compile-time-form? name))
            node
            (accumulate [found nil k v (each-pair node) &until found]
              (or (find-forbidden k (+ depth 1)) (find-forbidden v (+ depth 1))))))))

(local global-forms {:global true :set-forcibly! true})

(fn refusal [file name node]
  "The message for the refused form `name` at `node` of `file`."
  (let [src (fennel.ast-source node)]
    (.. file (if src.line (.. ":" src.line) "") ": (" (text.escape name)
        " ...) is not allowed: scene files are data and "
        (if (. global-forms name) "set no globals" "run no compile-time code"))))

(fn check-forms [forms file]
  "A message when the parsed `forms` use a refused form or nest too deeply, else nil."
  (var message nil)
  (each [_ form (ipairs forms) &until message]
    (case (find-forbidden form 1)
      :too-deep (set message (nesting-message file nil))
      node (set message (refusal file (tostring (. node 1)) node))))
  message)

(fn parse [source file]
  "All top-level forms of `source`, or nil when it does not parse (compiling it then
reports the parse error with its line)."
  (let [(ok? forms) (pcall #(icollect [_ form (fennel.parser (fennel.string-stream source) file)]
                              form))]
    (when ok? forms)))

;;; Compiling, with the compiler's shared state checked

;; Read once: the step hook calls them, and a module loaded with an :env (the tests,
;; tools/fnl.lua) reaches every global through a function.
(local gc collectgarbage)
(local cpu-clock os.clock)

(fn steps-text [n]
  (if (>= n 1e6) (.. (math.floor (/ n 1e6)) " million") (tostring (math.floor n))))


;; The check above reads the forms as written; a macro can still build a refused form
;; (-> x eval-compiler) is (eval-compiler x). So the scene is compiled in a scope
;; where every special form and macro off the allowlist is a special form that
;; refuses it: the compiler itself stops at whatever the macros expand into.

(fn scene-scope [file]
  "A compiler scope for `file` in which each special form and macro that is not on
the allowlist is a special form raising a sandbox error that names it and its line.
Scopes made inside it inherit that through their metatables."
  (let [g (global-scope)
        scope (fennel.scope g)
        refused (collect [name (each-pair g.specials)] (values name true))]
    (each [name (each-pair g.macros)] (tset refused name true))
    (each [name (each-pair refused)]
      (when (not (. allowed-forms name))
        ;; false: not a macro here, so the call reaches the special form below.
        (tset scope.macros name false)
        (tset scope.specials name (fn [ast] (stop (refusal file name ast))))))
    scope))

(fn compiler-state []
  (let [g (global-scope)]
    {:specials (collect [k v (each-pair g.specials)] k v)
     :macros (collect [k v (each-pair g.macros)] k v)
     :fennel (collect [k v (each-pair fennel)] k v)}))

(fn restore! [live saved]
  "Put table `live` back to the copy `saved`; true when anything had changed."
  (var changed? false)
  (each [k v (each-pair live)]
    (when (not= v (. saved k)) (set changed? true) (tset live k (. saved k))))
  (each [k v (each-pair saved)]
    (when (not= v (rawget live k)) (set changed? true) (tset live k v)))
  changed?)

;; The compiler's own modules, for the state a stopped compile can leave behind:
;; utils.root (the options of the compile in progress) and compiler.scopes.macro
;; (the scope a macro expands in, set around each expansion).
(local fennel-utils (case (pcall require :fennel.utils) (true utils) utils))
(local fennel-compiler (case (pcall require :fennel.compiler) (true compiler) compiler))
;; This file's chunk name: a hook that fires in it is on the way out of the compiler.
(local own-source (. (debug.getinfo 1 :S) :source))

(fn within-limits [f file]
  "Call `f` (the compiler at work on `file`) with the JIT off, so the count hook sees
every instruction, and stop it past the compile step, memory or time limit. Returns
true and its value, or false and the error (a sandbox error when a limit stopped it)."
  (var hooks 0)
  (var stopped nil)
  ;; Whether the compile has had its one collection (see over-memory?).
  (var collected? false)
  (let [memory-ceiling (+ (gc :count) (* 1024 limits.compile-memory-mb))
        max-hooks (/ limits.compile-steps limits.compile-hook-every)
        cpu-start (cpu-clock)
        stop! (fn [message] (set stopped message) (stop message))
        ;; Past the ceiling, garbage included, the first time: collect and count
        ;; again. The garbage then is mostly what was there before the compile (a
        ;; process that did much else, such as the test suite's), which would
        ;; otherwise stop a compile well within its limits. Later the count includes
        ;; garbage again: a collection each time would cost up to 0.5 s.
        over-memory? (fn []
                       (and (> (gc :count) memory-ceiling)
                            (or collected?
                                (do (set collected? true)
                                    (gc)
                                    (> (gc :count) memory-ceiling)))))
        hook (fn []
               (if stopped
                   ;; Stopped inside a pcall of the compiler's own (a macro's
                   ;; expansion): raise again until it is out, but never here.
                   (when (not= own-source (. (debug.getinfo 2 :S) :source))
                     (stop stopped))
                   (do (set hooks (+ hooks 1))
                       ;; One message for both: which trips first can depend on when the
                       ;; collector last ran (the memory counts garbage, see
                       ;; over-memory?), and a file must give the same message every time.
                       (if (or (> hooks max-hooks) (over-memory?))
                           (stop! (.. file ": compiling went past its limits ("
                                      (steps-text limits.compile-steps) " steps or "
                                      limits.compile-memory-mb
                                      " MB) and was stopped (macros that copy their arguments, nested too deep?)"))
                           (and (= 0 (% hooks 256))
                                (> (- (cpu-clock) cpu-start) limits.compile-cpu-seconds))
                           (stop! (.. file ": compiling took more than "
                                      limits.compile-cpu-seconds " s and was stopped"))))))
        jit-was-on? (and jit (jit.status))]
    ;; Off, and the traces compiled so far flushed: code that runs in a trace is
    ;; not seen by the count hook, and which of the compiler's functions have
    ;; traces depends on what the process did before (and on where LuaJIT's hot
    ;; counters fall): the same file counted 39 million steps in one run and over
    ;; 50 million in another, of 86 million in all.
    (when jit (jit.off) (jit.flush))
    (let [(outer-ok? ok? value) (pcall (fn []
                                         (debug.sethook hook "" limits.compile-hook-every)
                                         (let [(ok? value) (pcall f)]
                                           (debug.sethook)
                                           (values ok? value))))]
      (debug.sethook)
      (when jit-was-on? (jit.on))
      (if stopped (values false {:sandbox marker :message stopped})
          (not outer-ok?) (values false ok?)
          (values ok? value)))))

(fn compile [source file allowed]
  "Lua code for scene `source`, or nil and Fennel's message (or a sandbox error: a
refused form after macros expand, a compile limit). The compiler's special forms,
macros and module table are the same afterwards, whatever happened."
  (let [before (compiler-state)
        root (?. fennel-utils :root)
        ;; A list, not a table with keys: most of these are nil between compiles.
        saved-root (when root [root.chunk root.scope root.options root.reset])
        scopes (?. fennel-compiler :scopes)
        macro-scope (?. scopes :macro)
        (ok? code) (within-limits
                    #(fennel.compile-string source
                                            {:filename file :allowedGlobals allowed
                                             :correlate true :scope (scene-scope file)})
                    file)
        g (global-scope)
        ;; Restore all three: no short-circuit.
        changes [(restore! g.specials before.specials) (restore! g.macros before.macros)
                 (restore! fennel before.fennel)]
        changed? (or (. changes 1) (. changes 2) (. changes 3))]
    ;; The compiler resets its state on its own errors only; a refused form or a
    ;; limit stops it anywhere (inside a macro's expansion too), and the next compile
    ;; must not inherit the scene's options (its allowed globals) or scope.
    (when (and saved-root (not ok?))
      (set (root.chunk root.scope root.options root.reset)
           (values (. saved-root 1) (. saved-root 2) (. saved-root 3) (. saved-root 4))))
    (when scopes (set scopes.macro macro-scope))
    (if changed? (values nil (.. file ": the scene changed the Fennel compiler and was refused"))
        ok? code
        (values nil code))))

;;; The environment

;; The file of the scene running now, for the line in a capped call's message.
(local capped-files [])

(fn scene-line [file]
  "The line of the scene's own code that is running now, from the call stack."
  (var line nil)
  (for [level 3 40 &until line]
    (case (debug.getinfo level :Sl)
      info (when (= info.source (.. "@" file)) (set line info.currentline))))
  line)

(fn refuse [what why]
  ;; A library call refused before it runs, naming the scene's line.
  (let [file (. capped-files 1)
        line (and file (scene-line file))]
    (error (.. (if line (.. file ":" line ": ") (if file (.. file ": ") "")) what ": " why)
           0)))

(fn capped [what size]
  (when (> size limits.string-bytes)
    (refuse what "the result would be over 1 MB")))

(fn as-text [v]
  ;; What string.rep makes of a number it is given as a string.
  (if (= (type v) :number) (tostring v) v))

(fn safe-rep [str n ?sep]
  (let [count (or (tonumber n) 0)
        str (as-text str)
        sep (as-text ?sep)]
    (when (and (= (type str) :string) (or (= sep nil) (= (type sep) :string)))
      (capped "string.rep" (* (+ (length str) (length (or sep ""))) count)))
    (string.rep str n sep)))

(fn safe-insert [t ...]
  ;; table.insert at a position moves the elements after it one by one, in C: a
  ;; position far below 1 is a loop of billions of steps that no hook sees. As in Lua
  ;; 5.3, the position is a whole number from 1 to the list's length plus one.
  (when (and (= (type t) :table) (= (select :# ...) 2))
    (let [pos (select 1 ...)
          top (+ (length t) 1)]
      (when (not (and (= (type pos) :number) (= pos (math.floor pos)) (<= 1 pos top)))
        (refuse "table.insert" (.. "position " (tostring pos) " is out of bounds (1 to " top ")")))))
  (table.insert t ...))

(fn safe-format [fmt ...]
  ;; Each argument is at most its own length twice (%q escapes), a number 99 digits
  ;; (the widest format Lua allows), anything else its tostring.
  (when (= (type fmt) :string)
    (var size (length fmt))
    (for [i 1 (select :# ...)]
      (let [v (select i ...)]
        (set size (+ size 100 (if (= (type v) :string) (* 2 (length v)) 0)))))
    (capped "string.format" size))
  (string.format fmt ...))

(fn safe-concat [t ?sep ?i ?j]
  (when (= (type t) :table)
    (let [i (or (tonumber ?i) 1)
          j (or (tonumber ?j) (length t))
          sep (let [sep (as-text ?sep)] (if (= (type sep) :string) (length sep) 0))]
      (var size 0)
      (for [k i j &until (> size limits.string-bytes)]
        (let [v (. t k)]
          (set size (+ size sep (if (= (type v) :string) (length v) 24)))))
      (capped "table.concat" size)))
  (table.concat t ?sep ?i ?j))

(fn safe-env []
  "The only globals a scene file sees: arithmetic helpers and nothing that reaches
the file system, the process, the loader or the compiler."
  (let [m (collect [k v (each-pair math)] (when (and (not= k :randomseed) (not= k :random)) (values k v)))
        unpack (or table.unpack _G.unpack)]
    {:math m :ipairs ipairs :pairs pairs :tonumber tonumber :tostring tostring
     :type type :select select :unpack unpack
     :table {:insert safe-insert :concat safe-concat :unpack unpack}
     :string {:format safe-format :sub string.sub :rep safe-rep}}))

;;; Running, within limits

(fn run [chunk file env ?options]
  "Call `chunk` with the JIT off (so the count hook fires) and stop it with a clear
message past the step or memory limit. Returns true and the value, or false and an
error (a string from the scene's code, or a sandbox error); third, about how many
steps it took (counted every limits.hook-every). The step limit grows with the data
the scene builds: limits.steps, and limits.steps-per-kb more for each KB of Lua
memory it has reached (its highest count, garbage included); the time backstop grows
with it. `?options`: :steps (a fixed step limit, for the functions of time called
every frame) and :collect? (false: no full garbage collection afterwards, also for
those calls)."
  (var hooks 0)
  (var stopped nil)
  (let [options (or ?options {})
        steps (or options.steps limits.steps)
        ;; Garbage left from before (the compile's) collected first: the step limit
        ;; grows with memory above this count, and garbage collected while the scene
        ;; runs would otherwise have to be built again before its data earned a step.
        start-kb (if options.steps (gc :count) (do (gc) (gc :count)))
        memory-ceiling (+ start-kb (* 1024 limits.memory-mb))
        base-hooks (/ steps limits.hook-every)
        hooks-per-kb (if options.steps 0 (/ limits.steps-per-kb limits.hook-every))
        cpu-start (cpu-clock)
        stop! (fn [message]
                ;; Raise once: a hook firing again on the way out of pcall (before the
                ;; hook is removed) must not raise outside it.
                (set stopped message)
                (stop message))]
    (var max-hooks base-hooks)
    (var peak-kb start-kb)
    (let [;; The hook runs every few instructions, most of a generated scene's load:
          ;; upvalues and locals only, and the rare tests last.
          hook (fn []
                 (when (not stopped)
                   (set hooks (+ hooks 1))
                   (let [kb (gc :count)]
                     (when (> kb peak-kb)
                       (set peak-kb kb)
                       (set max-hooks (+ base-hooks (* hooks-per-kb (- kb start-kb)))))
                     (if (> hooks max-hooks)
                         (stop! (.. file ": the scene ran for more than "
                                    (steps-text (* max-hooks limits.hook-every))
                                    " steps and was stopped (an endless loop?)"))
                         (> kb memory-ceiling)
                         (stop! (.. file ": the scene built more than " limits.memory-mb
                                    " MB of data and was stopped"))
                         (and (= 0 (% hooks 65536))
                              (> (- (cpu-clock) cpu-start)
                                 (* limits.cpu-seconds (/ max-hooks base-hooks))))
                         (stop! (.. file ": the scene ran for more than "
                                    (math.floor (* limits.cpu-seconds (/ max-hooks base-hooks)))
                                    " s and was stopped"))))))
        string-meta (getmetatable "")
        real-index string-meta.__index]
    (when jit (jit.off chunk true))
    (when setfenv (setfenv chunk env))
    ;; Methods on strings, (: "x" :rep n), go through the string metatable to the real
    ;; string library: point it at the sandbox's own for the run.
    (set string-meta.__index env.string)
    (tset capped-files 1 file)
    (let [(outer-ok? ok? value) (pcall (fn []
                                         (debug.sethook hook "" limits.hook-every)
                                         (let [(ok? value) (pcall chunk)]
                                           (debug.sethook)
                                           (values ok? value))))]
      (debug.sethook)
      (set string-meta.__index real-index)
      (tset capped-files 1 nil)
      (when (not= false options.collect?) (collectgarbage))
      (let [used (* hooks limits.hook-every)]
        (if stopped (values false {:sandbox marker :message stopped} used)
            (not outer-ok?) (values false ok? used)
            (values ok? value used)))))))

(fn error-message [e]
  "The text of an error raised while loading: a sandbox message, a string, or a
fixed description for anything else (never calling a metamethod of it)."
  (if (sandbox-error? e) (rawget e :message)
      (= (type e) :string) e
      "the scene raised an error that is not a message"))

{: limits : check-source : check-encoding : nesting-message : nesting-line : check-forms : parse : compile : safe-env : run
 : error-message : sandbox-error?}

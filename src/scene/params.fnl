;; Parameters: a scene file marks a value as one with (param :name value {:min :max}).
;; While a scene loads, each call records the parameter and gives its value (or the
;; player's override of it); the player shows a slider, colour or checkbox for each,
;; and "save" writes the current values back into the file, changing only the
;; literals of those calls: comments, layout and everything else stay byte for byte.
;; Pure: runs under plain LuaJIT.

(local fennel (require :fennel))
(local text (require :src.util.text))
(local output (require :src.util.output))
;; `pairs` under another name: a loop over `pairs` by that name is LuaJIT's ITERN,
;; which Debian 12's LuaJIT ends early once despecialised (see src/util/wire.fnl).
(local each-pair pairs)

(local max-params 64)   ; rows a panel can show and a person can use

;;; Kinds and checks (at load, inside the scene's own run)

(fn finite? [v]
  (and (= (type v) :number) (= v v) (not= v math.huge) (not= v (- math.huge))))

(fn triple? [v]
  (and (= (type v) :table) (= (length v) 3) (finite? (. v 1)) (finite? (. v 2)) (finite? (. v 3))
       (= nil (next v 3))))

(fn kind-of [value opts]
  "The parameter's kind from its value and options: :number, :switch, :colour or
:vector (three numbers with :min and :max); or nil and why not."
  (if (finite? value) :number
      (= (type value) :boolean) :switch
      (triple? value) (if (not= nil opts.min) :vector :colour)
      (values nil (.. "the value must be a number, true or false, or three numbers like [1 0.5 0.2]"))))

(fn check-spec [kind value opts]
  "nil when `value` with `opts` makes a parameter of `kind`, else the reason."
  (case kind
    (where (or :number :vector))
    (if (not (and (finite? opts.min) (finite? opts.max)))
        (.. "a " (if (= kind :number) "number" "vector") " parameter needs {:min A :max B}")
        (>= opts.min opts.max) ":min must be below :max"
        (accumulate [bad nil _ v (ipairs (if (= kind :number) [value] value)) &until bad]
          (when (not (<= opts.min v opts.max))
            (.. "the value " (tostring v) " is outside :min " opts.min " :max " opts.max))))
    :colour (when (not (accumulate [ok? true _ v (ipairs value)] (and ok? (<= 0 v 1))))
              "a colour has three numbers from 0 to 1 (give :min and :max for a vector)")
    :switch nil))

(fn copy [v]
  (if (= (type v) :table) [(. v 1) (. v 2) (. v 3)] v))

(fn same-kind? [kind v]
  (case kind
    :number (finite? v)
    :switch (= (type v) :boolean)
    _ (triple? v)))

(fn clamp-to [p v]
  ;; An override outside the range (a file edited to a narrower one) is pulled in.
  (case p.kind
    :number (math.max p.min (math.min p.max v))
    :vector (icollect [_ c (ipairs v)] (math.max p.min (math.min p.max c)))
    :colour (icollect [_ c (ipairs v)] (math.max 0 (math.min 1 c)))
    _ v))

(fn same-value? [a b]
  (if (and (= (type a) :table) (= (type b) :table))
      (and (= (. a 1) (. b 1)) (= (. a 2) (. b 2)) (= (. a 3) (. b 3)))
      (= a b)))

(fn collector [?overrides]
  "A fresh record of the parameters of one load. `?overrides` maps names to
{:value v :base b}: the value to give instead of the file's (the player's slider
position), as long as the file still says `b` (an edit of that literal in an editor
wins over a slider moved before it)."
  {:list [] :by-name {} :overrides (or ?overrides {})})

(fn param-function [rec]
  "The `param` a scene calls: (param :name value ?options) checks the parameter,
records it in `rec` and returns its value (the override when there is one). A
mistake raises a message naming the parameter, and leaves the name in
`rec.failed` (see `failure-line`)."
  (fn [name value ?opts]
    ;; This runs inside the scene's sandbox, where strings have only the sandbox's
    ;; methods: string functions are called directly.
    (let [name? (and (= (type name) :string) (<= (length name) 40)
                     (string.match name "^[%a_][%w_%-]*$"))
          fail (fn [why]
                 (let [message (.. "(param " (if name? (.. ":" name " ...") "...") "): " why)]
                   (set rec.failed {:name (and name? name) : message})
                   (error message 0)))
          opts (if (= ?opts nil) {} ?opts)]
      (when (not name?)
        (fail "the first argument is the parameter's name, like :radius"))
      (when (not= (type opts) :table) (fail "the options must be a table like {:min 0 :max 1}"))
      (each [k (each-pair opts)]
        (when (and (not= k :min) (not= k :max))
          (fail "unknown option; the options are :min and :max")))
      (let [(kind why) (kind-of value opts)]
        (when (not kind) (fail why))
        (case (check-spec kind value opts) why (fail why))
        (let [known (. rec.by-name name)]
          (if known
              (when (or (not= known.kind kind) (not= known.min opts.min) (not= known.max opts.max))
                (fail "the same name is used with another kind or range"))
              (do (when (>= (length rec.list) max-params)
                    (fail (.. "a scene has at most " max-params " parameters")))
                  (let [p {: name : kind :default (copy value) :min opts.min :max opts.max}
                        o (. rec.overrides name)
                        use? (and (= (type o) :table) (same-kind? kind o.value)
                                  (same-value? o.base value))]
                    (set p.value (if use? (clamp-to p o.value) (copy value)))
                    (table.insert rec.list p)
                    (tset rec.by-name name p))))
          (copy (. rec.by-name name :value)))))))

;;; Where the literals are: a small reader over the file's text

(fn delimiter? [c]
  (or (= c "") (c:match "[%s%(%)%[%]{}\";]")))

(fn skip-space [source i]
  "The position of the next token at or after `i`: past white space and comments."
  (var i i)
  (var done? false)
  (while (not done?)
    (let [c (source:sub i i)]
      (if (c:match "%s") (set i (+ i 1))
          (= c ";") (set i (or (source:find "\n" i true) (+ (length source) 1)))
          (set done? true))))
  i)

(fn token-end [source i]
  "The position just past the atom (number, symbol, keyword, string) starting at `i`."
  (if (= (source:sub i i) "\"")
      (do (var j (+ i 1))
          (while (and (<= j (length source)) (not= (source:sub j j) "\""))
            (set j (+ j (if (= (source:sub j j) "\\") 2 1))))
          (+ j 1))
      (do (var j i)
          (while (not (delimiter? (source:sub j j))) (set j (+ j 1)))
          j)))

(fn literal-spans [source start kind]
  "Byte spans [from to) of the value literal of the (param ...) call whose ( is at
`start`: one span for a number or switch, three for the numbers inside [ ]; or nil
when the value is not written as a literal."
  (let [at-name (skip-space source (token-end source (+ start 1)))   ; past "(param"
        at-value (skip-space source (token-end source at-name))]
    (case kind
      (where (or :number :switch))
      (let [stop (token-end source at-value)
            word (source:sub at-value (- stop 1))]
        (when (if (= kind :number) (tonumber word) (or (= word "true") (= word "false")))
          [[at-value stop]]))
      _ (when (= (source:sub at-value at-value) "[")
          (var i (skip-space source (+ at-value 1)))
          (local spans [])
          (for [_ 1 3]
            (let [stop (token-end source i)]
              (table.insert spans [i stop])
              (set i (skip-space source stop))))
          (when (and (= (source:sub i i) "]")
                     (accumulate [ok? true _ [a b] (ipairs spans)] (and ok? (tonumber (source:sub a (- b 1))))))
            spans)))))

(fn param-call? [node]
  (and (fennel.list? node) (fennel.sym? (. node 1)) (= (tostring (. node 1)) "param")))

(fn find-calls [node found depth]
  (when (and (= (type node) :table) (not (fennel.sym? node)) (< depth 200))
    (when (param-call? node) (table.insert found node))
    (each [k v (each-pair node)]
      (find-calls k found (+ depth 1))
      (find-calls v found (+ depth 1))))
  found)

(fn failure-line [source file rec]
  "The line of the (param ...) call that failed while `source` ran (see
param-function): the call with that name, else the first one whose name is not
written out; nil when there is none."
  (let [(ok? forms) (pcall #(icollect [_ f (fennel.parser (fennel.string-stream source) file)] f))
        calls (if ok? (find-calls forms [] 0) [])
        want (?. rec :failed :name)]
    (table.sort calls #(< $1.bytestart $2.bytestart))
    (or (accumulate [line nil _ call (ipairs calls) &until line]
          (when (and want (= (. call 2) want)) call.line))
        ;; A name made in code: the first call whose name is not written out.
        (accumulate [line nil _ call (ipairs calls) &until line]
          (when (not= (type (. call 2)) :string) call.line)))))

(fn sites [source file]
  "The (param ...) calls written in `source`, by name: {name {:line :start}}; or nil
and 'file:line: reason' when a name is not written as a literal or is used twice."
  (let [(ok? forms) (pcall #(icollect [_ f (fennel.parser (fennel.string-stream source) file)] f))
        calls (if ok? (find-calls forms [] 0) [])
        out {}]
    (table.sort calls #(< $1.bytestart $2.bytestart))
    (var err nil)
    (each [_ call (ipairs calls) &until err]
      (let [name (. call 2)
            where (.. file ":" (or call.line "?"))]
        (if (not= (type name) :string)
            (set err (.. where ": (param ...): the name must be written as a keyword like :radius"))
            (. out name)
            (set err (.. where ": (param " (text.keyword name) " ...): the name is already used on line "
                         (. out name :line) "; each parameter is written once"))
            (tset out name {:line call.line :start call.bytestart}))))
    (if err (values nil err) out)))

;;; Writing values back

(fn loaded-number [literal]
  ;; The number a scene gets for `literal`. The compiler writes a number into Lua with
  ;; tostring, which keeps 14 significant digits under LuaJIT: that is what loads.
  (let [(ok? code) (pcall fennel.compile-string literal)]
    (and ok? (tonumber (code:match "^return%s+(.-)%s*$")))))

(fn number-literal [v ?min ?max]
  ;; The shortest literal that loads as exactly the number it reads as: `v` itself when
  ;; the compiler keeps it, else the nearest number it does keep; within [?min, ?max]
  ;; (the loaded bounds, which the compiler keeps), so a value at an edge is the edge.
  (let [loads-as (or (loaded-number (string.format "%.17g" v)) v)
        target (math.max (or ?min loads-as) (math.min (or ?max loads-as) loads-as))
        s (or (faccumulate [s nil digits 1 17 &until s]
                (let [s (string.format (.. "%." digits "g") target)]
                  (when (and (= (tonumber s) target) (= (loaded-number s) target)) s)))
              (string.format "%.17g" target))]
    (if (= target 0) "0" s)))

(fn replace-spans [source edits]
  "`source` with each {:from :to :with} edit applied (spans do not overlap)."
  (table.sort edits #(> $1.from $2.from))
  (var out source)
  (each [_ e (ipairs edits)]
    (set out (.. (out:sub 1 (- e.from 1)) e.with (out:sub e.to))))
  out)

(fn write-back [source file params]
  "The text of `source` with each parameter in `params` (a list of {:name :kind
:value}) written into its (param ...) literal. A literal whose number already has
the value keeps its spelling. Returns the text and the count of literals changed, or
nil and 'file:line: reason'."
  (case (sites source file)
    (nil err) (values nil err)
    found
    (do (var err nil)
        (local edits [])
        (each [_ p (ipairs params) &until err]
          (let [site (. found p.name)]
            (if (not site)
                (set err (.. file ": the parameter " (text.keyword p.name) " is no longer in the file"))
                (case (literal-spans source site.start p.kind)
                  nil (set err (.. file ":" site.line ": (param " (text.keyword p.name)
                                   " ...): its value is not written as a literal, so it cannot be saved"))
                  spans (let [vals (if (= (type p.value) :table) p.value [p.value])]
                          (each [i [from to] (ipairs spans)]
                            (let [old (source:sub from (- to 1))
                                  v (. vals i)
                                  new (if (= (type v) :boolean) (tostring v)
                                          (= (tonumber old) v) old
                                          (number-literal v p.min p.max))]
                              (when (not= new old)
                                (table.insert edits {: from : to :with new})))))))))
        (if err (values nil err)
            (values (replace-spans source edits) (length edits))))))

(fn save! [path params ?read]
  "Write the values of `params` into the scene file at `path`, atomically (see
output.write!: a new file created exclusively beside it, renamed over it; a scene
opened through links is saved into the file they lead to, and the links stay),
re-reading the file first so edits made since it was loaded are kept. Returns the
count of literals changed, or nil and a message."
  (let [(source rerr) (if ?read (?read path)
                          (case (io.open path :rb)
                            f (let [s (f:read :*a)] (f:close) s)
                            (nil e) (values nil e)))]
    (if (not source)
        (values nil (.. path ": cannot read the scene file to save: " (tostring rerr)))
        (case (write-back source path params)
          (nil err) (values nil err)
          (_ 0) 0
          (new-text n) (case (output.write! path new-text)
                         true n
                         (nil err) (values nil err))))))

{: collector : param-function : failure-line : same-value? : sites : write-back : save!}

;; The wire format between the scene worker and the player: plain data (nested tables
;; of strings, numbers and booleans) as bytes, and back through a strict parser that
;; never runs what it reads (no `load`). Numbers travel as raw IEEE doubles (exact,
;; fast: a scene can hold millions), strings once each.
;;
;; Layout:
;;   "SDW1 <nstrings> <nnumbers> <nops>\n"
;;   the strings, each "<len>:" and then exactly len bytes (any bytes)
;;   the numbers, nnumbers doubles of 8 bytes in native byte order
;;   the ops, one byte each: `[` list, `{` map, `}` end of the innermost list or map,
;;   `n` the next number, `s` a string (the next number is its 1-based index),
;;   `v` a list of numbers (the next number is how many, the numbers follow: a
;;   position or a colour in one op, not five), `t` true, `f` false.
;; One value, nothing after it. In a map, ops alternate key and value; keys are strings
;; or integers. Pure LuaJIT (needs the FFI). Failures are `nil, message`; decode
;; never raises, whatever the bytes.

(local ffi (require :ffi))

;; The decoder's defaults (and the encoder's :max-depth): tables nested at most
;; :max-depth deep (this also stops cycles when encoding), at most :max-bytes of data.
(local limits {:max-depth 100 :max-bytes (* 256 1024 1024)})

(local text (require :src.util.text))

;; Globals the loops call, read once: a module loaded with an :env (the tests,
;; tools/fnl.lua) reaches every global through a function.
(local type type)
;; `pairs` under another name: LuaJIT compiles a loop over pairs (or next) by that name
;; into its specialised ITERN bytecode, and Debian 12's LuaJIT (2.1 of 2022-03-20)
;; ends such a loop early once a trace is blacklisted and the loop despecialised
;; (LuaJIT issue 827, fixed upstream 2022-04): the encoder then sent a node of a
;; deep tree as an empty list, in about 1 of 6 fresh processes. A loop over a local
;; of another name is a plain iterator call.
(local each-pair pairs)
(local ipairs ipairs)
(local tostring tostring)
(local pcall pcall)
(local concat table.concat)
(local sort table.sort)
(local insert table.insert)
(local sbyte string.byte)
(local ssub string.sub)
(local floor math.floor)
(local huge math.huge)
(local neg-huge (- math.huge))

(local op-list (sbyte "["))
(local op-map (sbyte "{"))
(local op-end (sbyte "}"))
(local op-number (sbyte "n"))
(local op-string (sbyte "s"))
(local op-true (sbyte "t"))
(local op-false (sbyte "f"))
(local op-vector (sbyte "v"))
(local colon (sbyte ":"))
(local newline (sbyte "\n"))
(local space (sbyte " "))
(local zero (sbyte "0"))
(local nine (sbyte "9"))

(fn integer? [x]
  ;; A finite number without a fraction (NaN and ±inf are not).
  (and (= (type x) :number) (= x (floor x)) (< neg-huge x huge)))

;;; Encoding

(fn release! [...]
  "Empty each table given: scratch tables a closure of encode or decode holds, which a
JIT trace may keep alive after the call."
  (each [_ t (ipairs [...])]
    (each [k (each-pair t)] (tset t k nil))))

(fn key-before? [a b]
  ;; Strings before numbers, each ascending.
  (let [ta (type a)]
    (if (= ta (type b)) (< a b) (= ta :string))))

(fn path-text [path depth]
  ;; path[1..depth] joined by dots, string keys escaped; a long path (a cycle) shows
  ;; its first and last keys.
  (let [parts (fcollect [i 1 depth]
                (if (and (> depth 12) (< 8 i (- depth 2))) false
                    (= (type (. path i)) :string) (text.escape (. path i))
                    (tostring (. path i))))]
    (if (= depth 0) "the top"
        (> depth 12)
        (.. (concat parts "." 1 8) "... (" depth " keys) ..." (concat parts "." (- depth 2) depth))
        (concat parts "."))))

(fn key-text [k]
  (if (= (type k) :number) (.. "the key " (tostring k)) (.. "a " (type k) " key")))

(fn encode-parts [value ?limits]
  "The bytes of `value` in the wire format (see encode) as a list of strings whose
concatenation they are, and their total length: a sender writes them one after
another without the copy that joins them (a 140 MB answer was held three times)."
  (let [max-depth (or (and ?limits (. ?limits :max-depth)) limits.max-depth)
        strings []
        index {}
        path []]
    (var ns 0)
    (var nn 0)
    (var no 0)
    (var err nil)
    ;; Numbers and ops go straight into buffers that double when full.
    (var num-cap 1024)
    (var nums (ffi.new "double[?]" num-cap))
    (var op-cap 1024)
    (var ops (ffi.new "uint8_t[?]" op-cap))

    (fn put-num [x]
      ;; One more double, with no op of its own.
      (when (>= nn num-cap)
        (let [bigger (ffi.new "double[?]" (* 2 num-cap))]
          (ffi.copy bigger nums (* 8 nn))
          (set nums bigger)
          (set num-cap (* 2 num-cap))))
      (tset nums nn x)
      (set nn (+ nn 1)))

    (fn put-op [op]
      (when (>= no op-cap)
        (let [bigger (ffi.new "uint8_t[?]" (* 2 op-cap))]
          (ffi.copy bigger ops no)
          (set ops bigger)
          (set op-cap (* 2 op-cap))))
      (tset ops no op)
      (set no (+ no 1)))

    (fn put-string [s]
      (var i (. index s))
      (when (not i)
        (set ns (+ ns 1))
        (set i ns)
        (tset index s i)
        (tset strings ns (.. (length s) ":" s)))
      (put-num i)
      (put-op op-string))

    (fn put-number [x]
      (put-num x)
      (put-op op-number))

    (fn walk [v depth]
      ;; `depth`: how many tables hold `v`; path[1..depth] leads to it.
      (let [t (type v)]
        (if (= t :number) (put-number v)
            (= t :string) (put-string v)
            (= v true) (put-op op-true)
            (= v false) (put-op op-false)
            (= t :table)
            (if (>= depth max-depth)
                (set err (.. "nested deeper than " max-depth " at " (path-text path depth)))
                (let [n (length v)
                      inner (+ depth 1)]
                  (var count 0)
                  (var list? true)
                  (each [k (each-pair v) &until (not list?)]
                    (set count (+ count 1))
                    (when (not (and (= (type k) :number) (>= k 1) (<= k n) (= k (floor k))))
                      (set list? false)))
                  (var numbers? (and list? (= count n) (> n 0)))
                  (for [i 1 n &until (not numbers?)]
                    (when (not= (type (. v i)) :number) (set numbers? false)))
                  (if numbers?
                      (do (put-op op-vector)
                          (put-num n)
                          (for [i 1 n] (put-num (. v i))))
                      (and list? (= count n))
                      (do (put-op op-list)
                          (for [i 1 n &until err]
                            (tset path inner i)
                            (walk (. v i) inner))
                          (put-op op-end))
                      (let [keys []]
                        (var strings? true)
                        (var nk 0)
                        (each [k (each-pair v) &until err]
                          (if (= (type k) :string) (do (set nk (+ nk 1)) (tset keys nk k))
                              (integer? k) (do (set nk (+ nk 1)) (tset keys nk k) (set strings? false))
                              (set err (.. "cannot send " (key-text k) " at "
                                           (path-text path depth)
                                           " (keys are strings or integers)"))))
                        (when (not err)
                          ;; String keys alone (the usual map) sort without a
                          ;; comparator function, which is faster.
                          (if strings? (sort keys) (sort keys key-before?))
                          (put-op op-map)
                          (for [j 1 nk &until err]
                            (let [k (. keys j)]
                              (if (= (type k) :string) (put-string k) (put-number k))
                              (tset path inner k)
                              (walk (. v k) inner)))
                          (put-op op-end))))))
            (set err (.. "cannot send a " t " at " (path-text path depth))))))

    (walk value 0)
    (let [result (when (not err)
                   [(.. "SDW1 " ns " " nn " " no "\n" (concat strings))
                    (ffi.string nums (* 8 nn)) (ffi.string ops no)])]
      ;; The closures above may outlive this call in a JIT trace that took them as
      ;; constants (LuaJIT anchors a trace's constants): what they hold goes now, or
      ;; the number buffer (64 MB for 1,000,000 spheres) stayed until the trace did.
      (release! strings index path)
      (set (nums ops) (values nil nil))
      (if err (values nil err)
          (values result (accumulate [n 0 _ part (ipairs result)] (+ n (length part))))))))

(fn encode [value ?limits]
  "The bytes of `value` (strings, numbers, booleans and tables of them) in the wire
format, deterministic (map keys sorted). A table is a list when its keys are exactly
1..(length t) and there is at least one; an empty table is an empty list; any other
table is a map, with string or integer keys. `?limits`: :max-depth (default 100).
Returns the string, or nil and 'cannot send a <type> at <path>', 'cannot send <key>
at <path>' or 'nested deeper than <max-depth> at <path>' (path: keys joined by dots)."
  (case (encode-parts value ?limits)
    parts (concat parts)
    (nil err) (values nil err)))

;;; Decoding

(fn read-count [s pos stop]
  ;; A decimal count at `pos` (1 to 15 digits, no leading zero) ended by the byte
  ;; `stop`: the count and the position after `stop`, or nil.
  (var i pos)
  (var x 0)
  (var c (sbyte s i))
  (while (and c (<= zero c nine) (< (- i pos) 15))
    (set x (+ (* x 10) (- c zero)))
    (set i (+ i 1))
    (set c (sbyte s i)))
  (when (and (> i pos) (= c stop) (or (= i (+ pos 1)) (not= (sbyte s pos) zero)))
    (values x (+ i 1))))

(fn malformed [msg]
  (values nil (.. "malformed data: " msg)))

(fn decode-ops [s ops-at size numbers nn strings ns max-depth]
  ;; The one value the ops at `ops-at`..`size` build, or nil and why.
  (let [stack []        ; the open tables, innermost last
        maps []         ; true where stack[d] is a map
        counts []       ; a list's values so far
        keys []]        ; a map's key waiting for its value (nil when none)
    (var depth 0)
    (var root nil)
    (var done? false)
    (var ni 0)
    (var err nil)
    (var i ops-at)

    (fn put [v]
      ;; Place value `v` where the ops say; a new table goes in before its contents.
      (if (= depth 0)
          (do (set root v)
              ;; A table at the top is done when its } comes.
              (when (not= (type v) :table) (set done? true)))
          (not (. maps depth))
          (let [c (+ (. counts depth) 1)]
            (tset counts depth c)
            (tset (. stack depth) c v))
          (let [k (. keys depth)
                m (. stack depth)]
            (if (not= k nil)
                (do (tset m k v) (tset keys depth nil))
                (not (or (= (type v) :string) (integer? v)))
                (set err (.. "a map key is not a string or an integer ("
                             (if (= (type v) :number) (tostring v) (.. "a " (type v)))
                             ") at op " (- i ops-at -1)))
                (not= (. m v) nil)
                (set err (.. "duplicate key " (string.format "%q" (tostring v))
                             " at op " (- i ops-at -1)))
                (tset keys depth v)))))

    (fn next-number []
      (if (< ni nn)
          (let [x (. numbers ni)] (set ni (+ ni 1)) x)
          (do (set err (.. "more numbers used than the " nn " sent, at op " (- i ops-at -1)))
              0)))

    (while (and (<= i size) (not err))
      (let [c (sbyte s i)]
        (if done? (set err (.. "trailing bytes after the value, from op " (- i ops-at -1)))
            (= c op-number) (let [x (next-number)] (when (not err) (put x)))
            (= c op-string)
            (let [x (next-number)]
              (when (not err)
                (if (and (integer? x) (<= 1 x ns))
                    (put (. strings x))
                    (set err (.. "string index " (tostring x) " is not one of 1.." ns
                                 ", at op " (- i ops-at -1))))))
            (or (= c op-list) (= c op-map))
            (if (>= depth max-depth)
                (set err (.. "nested deeper than " max-depth " at op " (- i ops-at -1)))
                (let [t {}]
                  (put t)
                  (when (not err)
                    (set depth (+ depth 1))
                    (tset stack depth t)
                    (tset maps depth (= c op-map))
                    (tset counts depth 0)
                    (tset keys depth nil))))
            (= c op-end)
            (if (= depth 0)
                (set err (.. "unbalanced } at op " (- i ops-at -1)))
                (not= (. keys depth) nil)
                (set err (.. "a map ends after a key without its value, at op "
                             (- i ops-at -1)))
                (do (tset stack depth nil)
                    (set depth (- depth 1))
                    (when (= depth 0) (set done? true))))
            (= c op-vector)
            (let [n (next-number)]
              (when (not err)
                (if (not (and (integer? n) (<= 0 n (- nn ni))))
                    (set err (.. "a list of " (tostring n) " numbers, with "
                                 (- nn ni) " left, at op " (- i ops-at -1)))
                    (let [t {}]
                      (for [k 1 n]
                        (tset t k (. numbers ni))
                        (set ni (+ ni 1)))
                      (put t)
                      ;; A whole value: at the top, nothing may follow it.
                      (when (= depth 0) (set done? true))))))
            (= c op-true) (put true)
            (= c op-false) (put false)
            (set err (.. "unknown op byte " c " at op " (- i ops-at -1)
                         " (byte " i ")"))))
      (set i (+ i 1)))
    (let [value root]
      ;; As in encode: a trace may keep `put` and so its upvalues; `root` held the
      ;; whole decoded value (450 MB for 1,000,000 spheres) after the app dropped it.
      (set root nil)
      (release! stack maps counts keys)
      (if err (malformed err)
          (not done?) (malformed (if (= depth 0) "no value in the ops"
                                     (.. depth " lists or maps left open at the end")))
          (< ni nn) (malformed (.. (- nn ni) " of the " nn " numbers left unused"))
          value))))

(fn decode* [s ?limits]
  (let [max-depth (or (and ?limits (. ?limits :max-depth)) limits.max-depth)
        max-bytes (or (and ?limits (. ?limits :max-bytes)) limits.max-bytes)
        size (if (= (type s) :string) (length s) 0)]
    (if (not= (type s) :string) (malformed (.. "expected a string, got a " (type s)))
        (> size max-bytes) (malformed (.. size " bytes, more than the limit of " max-bytes))
        (not= (ssub s 1 5) "SDW1 ") (malformed "bad header (not \"SDW1 \")")
        (let [(ns p1) (read-count s 6 space)
              (nn p2) (when ns (read-count s p1 space))
              (no p3) (when nn (read-count s p2 newline))]
          (if (not no)
              (malformed "bad header (expected \"SDW1 <strings> <numbers> <ops>\\n\")")
              ;; Each string takes at least 2 bytes ("0:"), each number 8, each op 1.
              (> (+ (* 2 ns) (* 8 nn) no) (- size p3 -1))
              (malformed (.. "the header counts (" ns " strings, " nn " numbers, " no
                             " ops) need more than the " (- size p3 -1) " bytes after it"))
              (let [strings-end (- size (* 8 nn) no)   ; the last byte strings may use
                    strings []]
                (var pos p3)
                (var err nil)
                (for [k 1 ns &until err]
                  (let [(len at) (read-count s pos colon)]
                    (if (not len)
                        (set err (.. "bad length of string " k " at byte " pos))
                        (> (+ at len -1) strings-end)
                        (set err (.. "string " k " (" len " bytes at byte " at
                                     ") runs past the end of the strings"))
                        (do (tset strings k (ssub s at (+ at len -1)))
                            (set pos (+ at len))))))
                (if err (malformed err)
                    (not= pos (+ strings-end 1))
                    (malformed (.. "the counts do not match the length: "
                                   (- (+ strings-end 1) pos)
                                   " bytes between the strings and the numbers"))
                    ;; Read in place from `s` (held by the loop below): the doubles
                    ;; need not be 8-byte aligned, which x86-64 and arm64 allow.
                    (let [numbers (ffi.cast "const double*"
                                            (+ (ffi.cast "const char*" s) (- pos 1)))]
                      (decode-ops s (+ pos (* 8 nn)) size numbers nn strings ns
                                  max-depth)))))))))

(fn decode [s ?limits]
  "The value that the wire string `s` holds, read strictly (nothing in it is run).
`?limits`: :max-depth (default 100), :max-bytes (default 256 MiB). Returns the value,
(which may be false) or nil and 'malformed data: <what is wrong>'; never raises."
  (let [(ok? v msg) (pcall decode* s ?limits)]
    (if ok? (values v msg)
        (values nil (.. "malformed data: unexpected error: " (tostring v))))))

(fn frame [s]
  "`s` preceded by its byte length and a newline, for a stream of messages."
  (.. (length s) "\n" s))

{: encode : encode-parts : decode : frame : limits}

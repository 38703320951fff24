;; A strict reader for scene files that are plain data: one Fennel table literal of
;; numbers, strings, :keywords, true, false and tables, nothing else. Such a file needs
;; no compiler and no sandbox: nothing in it can run. Whatever this reader does not
;; accept (a list, a symbol, nil, a Lua escape it does not know, a duplicate key...)
;; is not data, and the file goes the way of code (src/scene/sandbox.fnl), which
;; reads every Fennel file as before. What it does accept, it reads as Fennel's parser
;; does: the same tables, keys and numbers (test/data_spec.fnl compares the two).
;;
;; Pure Lua: no LÖVE, no FFI.

;; Globals the loop calls, read once: a module loaded with an :env (the tests,
;; tools/fnl.lua) reaches every global through a function.
(local sbyte string.byte)
(local sfind string.find)
(local smatch string.match)
(local ssub string.sub)
(local schar string.char)
(local tonumber tonumber)
(local setmetatable setmetatable)
(local gc collectgarbage)
(local type type)
(local pcall pcall)
(local error error)
(local tostring tostring)
(local insert table.insert)
(local concat table.concat)

;; Bytes: whitespace as Fennel's parser has it (space, 9 to 13), brackets, and the
;; bytes that start an atom.
(local open-curly 123)
(local close-curly 125)
(local open-square 91)
(local close-square 93)
(local open-paren 40)
(local double-quote 34)
(local close-paren 41)
(local semicolon 59)
(local colon 58)

;; A symbol's bytes, as Fennel's parser reads them: above space, not a bracket, not
;; DEL, not " ' ~ ; , @ `. A keyword is a colon and one or more of them.
(local token-pattern "^([^%c ()%[%]{}\"'~;,@`]+)()")
;; The same as a table: true for the bytes that end a symbol (0 stands for the end).
(local symbol-end
  (let [t {}]
    (for [b 0 32] (tset t b true))
    (each [_ b (ipairs [127 40 41 91 93 123 125 34 39 126 59 44 64 96])] (tset t b true))
    t))
;; The bytes after which a plain number ends here: the end, whitespace, a closing
;; bracket, a comment. (Any other byte: the token is read whole and looked at.)
(local number-end {9 true 10 true 11 true 12 true 13 true 32 true 41 true 93 true
                   125 true 59 true})
;; Powers of ten, exact as doubles up to 1e22: (. powers (+ k 1)) is 10^k.
(local powers (fcollect [k 0 22] (^ 10 k)))

;; The string escapes read here, each the byte it stands for (Lua's own meaning).
;; Others (\x, \z, \u{}, a backslash before a line break) send the file to Fennel.
(local escapes {110 "\n" 116 "\t" 114 "\r" 97 "\a" 98 "\b" 102 "\f" 118 "\v"
                92 "\\" 34 "\"" 39 "'"})

(local memory-check-every 4096)   ; tables built between two looks at the memory

(fn not-data [why pos]
  ;; Raised inside the reader; `read` returns it.
  (error {:not-data why : pos} 0))

(fn refused [why pos]
  ;; A verdict that holds for code too (too deep, too large): no fallback.
  (error {:refused why : pos} 0))

(fn line-at [source pos]
  "The line of byte `pos` of `source` (1 for the first)."
  (let [(_ n) (: (ssub source 1 (- pos 1)) :gsub "\n" "")] (+ n 1)))

(fn read-string [source pos]
  ;; At the opening quote at `pos`: the string, escapes read, and the position after
  ;; its closing quote.
  (let [parts []]
    (var from (+ pos 1))
    (var after nil)
    (while (not after)
      (let [p (sfind source "[\"\\]" from)]
        (if (= p nil) (not-data "an unterminated string" pos)
            (= (sbyte source p) double-quote)
            (do (insert parts (ssub source from (- p 1)))
                (set after (+ p 1)))
            (let [c (sbyte source (+ p 1))
                  e (and c (. escapes c))]
              (insert parts (ssub source from (- p 1)))
              (if e (do (insert parts e) (set from (+ p 2)))
                  (and c (<= 48 c 57))
                  (let [(digits next) (smatch source "^(%d%d?%d?)()" (+ p 1))
                        code (tonumber digits)]
                    (when (> code 255) (not-data "a string escape past \\255" p))
                    (insert parts (schar code))
                    (set from next))
                  (not-data "a string escape this reader leaves to Fennel" p))))))
    (values (if (= 1 (length parts)) (. parts 1) (concat parts)) after)))

(fn read-plain-number [source pos]
  ;; At `pos`: a number of at most 15 digits with an optional minus sign and point
  ;; and nothing else, read byte by byte, and the position after it; else nil (the
  ;; token is read whole). Exact: the digits as a whole number (below 2^53) divided
  ;; by a power of ten (exact up to 1e22) is one correctly rounded division, as
  ;; tonumber's result is.
  (var i pos)
  (var c (sbyte source i))
  (var mantissa 0)
  (var digits 0)
  (var fraction 0)
  (let [negative? (= c 45)]
    (when negative? (set i (+ i 1)) (set c (sbyte source i)))
    (while (and c (<= 48 c 57))
      (set mantissa (+ (* mantissa 10) (- c 48)))
      (set digits (+ digits 1))
      (set i (+ i 1))
      (set c (sbyte source i)))
    (when (= c 46)
      (set i (+ i 1))
      (set c (sbyte source i))
      (while (and c (<= 48 c 57))
        (set mantissa (+ (* mantissa 10) (- c 48)))
        (set digits (+ digits 1))
        (set fraction (+ fraction 1))
        (set i (+ i 1))
        (set c (sbyte source i))))
    (when (and (< 0 digits 16) (or (= c nil) (. number-end c)))
      (let [x (if (= fraction 0) mantissa (/ mantissa (. powers (+ fraction 1))))]
        (values (if negative? (- x) x) i)))))

(fn read-token [source pos c]
  ;; A whole token at `pos` (its first byte `c`): true, false or a number tonumber
  ;; reads, and the position after it.
  (case (smatch source token-pattern pos)
    (tok after)
    (values (if (= tok "true") true
                (= tok "false") false
                ;; Plain decimal numbers only: no hex, no underscores, no .inf.
                (and (smatch tok "^[-+]?%.?%d") (not (sfind tok "[^%d%.eE+-]")))
                (case (tonumber tok)
                  x x
                  _ (not-data (.. "the token " tok) pos))
                (not-data (if (= tok "nil") "nil" (.. "the symbol " tok)) pos))
            after)
    _ (not-data (.. "the character " (schar c)) pos)))

(fn read-atom [source pos]
  ;; A number, a :keyword, true or false at `pos`, and the position after it.
  (let [c (sbyte source pos)]
    (if (= c colon)
        (do (var i (+ pos 1))
            (while (not (. symbol-end (or (sbyte source i) 0)))
              (set i (+ i 1)))
            (when (= i (+ pos 1)) (not-data "a colon that is not a keyword" pos))
            (values (ssub source (+ pos 1) (- i 1)) i))
        (let [(x after) (when (or (= c 45) (= c 46) (<= 48 c 57)) (read-plain-number source pos))]
          (if (= x nil) (read-token source pos c) (values x after))))))

(fn read [source ?options]
  "The value of `source` when it is one plain data table literal (see this file's
header): the value, read as Fennel reads it. Else nil and one of
  :not-data, why (a phrase), byte position  -- code or anything unsure: compile it
  :refused, why, byte position              -- past a limit that holds for code too
`?options`: :max-depth (brackets inside brackets, default 100), :max-memory-mb (Lua
memory the tables may take, garbage included, default none), :positions? (true:
each table gets Fennel's source fields, line, bytestart and byteend, in a metatable
as the parser gives them, for the loader's messages), :path (a list of keys, with
:positions?: only the tables along that path from the top are built, every other
table is read and stands as one shared empty table; for a message's line, a file
already read: a metatable per table took 290 MB more for 360,000 spheres written
out, and 1.9 million `{:kind :sphere}` peaked at 1.1 GB to say there were too many)."
  (let [options (or ?options {})
        max-depth (or options.max-depth 100)
        memory-ceiling (when options.max-memory-mb
                         (+ (gc :count) (* 1024 options.max-memory-mb)))
        positions? options.positions?
        path options.path
        path-length (if path (length path) 0)
        n (length source)]
    (var pos 1)
    (var tables 0)
    ;; Lines, counted forward only when positions are asked for.
    (var line 1)
    (var line-pos 1)

    (fn line-of [p]
      (when (< line-pos p)
        (let [(_ k) (: (ssub source line-pos (- p 1)) :gsub "\n" "")]
          (set line (+ line k))
          (set line-pos p)))
      line)

    (fn skip []
      ;; Past whitespace and comments; true when any was skipped.
      (let [start pos]
        (var more? true)
        (while more?
          (let [p (sfind source "[^\t-\r ]" pos)]
            (if (= p nil) (do (set pos (+ n 1)) (set more? false))
                (= (sbyte source p) semicolon)
                (set pos (let [e (sfind source "\n" p true)] (if e (+ e 1) (+ n 1))))
                (do (set pos p) (set more? false)))))
        (> pos start)))

    (fn counted! [t]
      ;; Every few thousand tables, the memory they take.
      (set tables (+ tables 1))
      (when (and memory-ceiling (= 0 (% tables memory-check-every))
                 (> (gc :count) memory-ceiling))
        (refused (.. "the file's data takes more than " options.max-memory-mb
                     " MB of memory") pos))
      t)

    (var read-value nil)

    (fn with-source [t start start-line end-pos]
      (when positions?
        (setmetatable t {:line start-line :bytestart start :byteend end-pos}))
      t)

    (fn read-items [closer depth on? level]
      ;; After an opening bracket: the forms up to `closer`, in order, and how many.
      ;; `on?`: the table is on options.path (`level` keys down it), or there is none.
      (let [items []
            curly? (= closer close-curly)]
        (var count 0)
        (var open? true)
        (var spaced? true)
        (while open?
          (let [skipped? (skip)
                c (sbyte source pos)]
            (if (= c nil) (not-data "an unclosed bracket" pos)
                (= c closer) (do (set pos (+ pos 1)) (set open? false))
                (or (= c close-curly) (= c close-square) (= c close-paren))
                (not-data "a mismatched closing bracket" pos)
                (not (or spaced? skipped?))
                (not-data "two forms with no space between them" pos)
                (let [key (if (not curly?) (+ count 1)
                              (= 0 (% count 2)) nil
                              (. items count))
                      child-on? (or (not path)
                                    (and on? (< level path-length) (not= nil key)
                                         (= key (. path (+ level 1)))))]
                  (set count (+ count 1))
                  (tset items count (read-value depth child-on? (+ level 1)))
                  (set spaced? false)))))
        (values items count)))

    ;; What a table off options.path stands for.
    (local skipped {})

    (set read-value
         (fn [depth ?on? ?level]
           (let [c (sbyte source pos)
                 on? (or (not path) ?on?)
                 level (or ?level 0)
                 start pos
                 ;; Counted before the contents move the count past `start`.
                 start-line (when positions? (line-of start))]
             (if (or (= c open-curly) (= c open-square))
                 (do (when (>= depth max-depth) (refused :too-deep pos))
                     (set pos (+ pos 1))
                     (if (not on?)
                         (do (read-items (if (= c open-square) close-square close-curly)
                                         (+ depth 1) false level)
                             skipped)
                         (= c open-square)
                         (let [(items) (read-items close-square (+ depth 1) on? level)]
                           (counted! (with-source items start start-line (- pos 1))))
                         (let [(items count) (read-items close-curly (+ depth 1) on? level)
                               t {}]
                           (when (not= 0 (% count 2))
                             (not-data "a table with an odd number of forms" start))
                           (for [i 1 count 2]
                             (let [k (. items i)]
                               (when (= (type k) :table)
                                 (not-data "a table as a key" start))
                               (when (not= nil (. t k))
                                 (not-data "a key given twice" start))
                               (tset t k (. items (+ i 1)))))
                           (counted! (with-source t start start-line (- pos 1))))))
                 (= c double-quote) (let [(v after) (read-string source pos)] (set pos after) v)
                 (= c open-paren) (not-data "a list (...): code" pos)
                 (let [(v after) (read-atom source pos)] (set pos after) v)))))

    (let [(ok? result) (pcall (fn []
                                (skip)
                                (when (> pos n) (not-data "no form" pos))
                                (let [value (read-value 0 true 0)]
                                  (skip)
                                  (when (<= pos n) (not-data "more than one form" pos))
                                  value)))]
      (if ok? result
          (and (= (type result) :table) result.not-data)
          (values nil :not-data result.not-data result.pos)
          (and (= (type result) :table) result.refused)
          (values nil :refused result.refused result.pos)
          ;; Lua's own failure (not enough memory, a stack overflow): not data we can
          ;; vouch for; the caller says so.
          (values nil :refused (tostring result) pos)))))

{: read : line-at}

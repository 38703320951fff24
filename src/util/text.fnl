;; Text that came from outside (scene files, their paths, command lines) made safe to
;; show: valid UTF-8 checks, and a quoted, shortened, escaped form for messages, the
;; terminal and the HUD. Pure: plain Lua strings in and out.

(local max-shown 40)   ; characters of a long value shown in a message

(fn utf8-length [s i]
  "Byte length of the UTF-8 sequence starting at byte `i` of `s`, or nil when the
bytes there are not a valid (shortest-form, non-surrogate) sequence."
  (let [c (s:byte i)]
    (if (< c 0x80) 1
        (let [(n lo hi) (if (<= 0xC2 c 0xDF) (values 2 0x80 0xBF)
                            (= c 0xE0) (values 3 0xA0 0xBF)
                            (= c 0xED) (values 3 0x80 0x9F)
                            (<= 0xE1 c 0xEF) (values 3 0x80 0xBF)
                            (= c 0xF0) (values 4 0x90 0xBF)
                            (<= 0xF1 c 0xF3) (values 4 0x80 0xBF)
                            (= c 0xF4) (values 4 0x80 0x8F)
                            (values nil))]
          (when n
            (let [c2 (s:byte (+ i 1))]
              (when (and c2 (<= lo c2 hi))
                (var ok? true)
                (for [k 2 (- n 1)]
                  (let [ck (s:byte (+ i k))]
                    (when (not (and ck (<= 0x80 ck 0xBF))) (set ok? false))))
                (when ok? n))))))))

(fn first-invalid-byte [s]
  "Byte position of the first byte of `s` that is not valid UTF-8 text or is a NUL,
or nil when the whole string is clean."
  (var i 1)
  (var bad nil)
  (let [n (length s)]
    (while (and (not bad) (<= i n))
      (let [len (utf8-length s i)]
        (if (or (not len) (= (s:byte i) 0)) (set bad i)
            (set i (+ i len))))))
  bad)

(fn valid-utf8? [s]
  "True when `s` is valid UTF-8 without NUL bytes."
  (= nil (first-invalid-byte s)))

(fn escape [s ?max ?quote?]
  "`s` with control characters, DEL and bytes that are not UTF-8 written as \\ddd
escapes (so no terminal escape or broken text can pass), cut after `?max` characters
(default 40) with the full byte length noted."
  (let [limit (or ?max max-shown)
        out []
        n (length s)]
    (var i 1)
    (var shown 0)
    (while (and (<= i n) (< shown limit))
      (let [c (s:byte i)
            len (utf8-length s i)]
        (if (or (not len) (< c 32) (= c 127))
            (do (table.insert out (case c
                                    10 "\\n" 9 "\\t" 13 "\\r"
                                    _ (string.format "\\%03d" c)))
                (set i (+ i 1)))
            (and ?quote? (= c 34)) (do (table.insert out "\\\"") (set i (+ i 1)))
            (and ?quote? (= c 92)) (do (table.insert out "\\\\") (set i (+ i 1)))
            (do (table.insert out (s:sub i (+ i len -1)))
                (set i (+ i len))))
        (set shown (+ shown 1))))
    (.. (table.concat out) (if (<= i n) (.. "... (" n " bytes)") ""))))

(fn quote-string [s ?max]
  "`s` in double quotes, escaped and shortened (see escape): for values in messages."
  (let [e (escape s ?max true)
        cut (e:find "... (" 1 true)]
    (if (and cut (e:match "%.%.%. %(%d+ bytes%)$"))
        (.. "\"" (e:sub 1 (- cut 1)) "\"" (e:sub cut))
        (.. "\"" e "\""))))

(fn name? [s]
  "True when `s` reads well as a :keyword (short, letters, digits, - _ ? !)."
  (and (= (type s) :string) (<= 1 (length s) max-shown)
       (not= nil (s:match "^[%a_][%w%-_%?!%.]*$"))))

(fn keyword [s]
  "`:s` when `s` is a plain name, else its quoted, escaped, shortened form."
  (if (name? s) (.. ":" s) (quote-string s)))

(fn printable [s ?max]
  "`s` made safe for a text display that needs valid UTF-8 (LÖVE's fonts): invalid
bytes and control characters (except newlines) become escapes; cut after `?max`
characters when given."
  (let [lines (icollect [line (: (.. s "\n") :gmatch "([^\n]*)\n")]
                (escape line (or ?max (+ (length line) 1))))]
    (table.concat lines "\n")))

(fn edit-distance [a b]
  "Edits that turn `a` into `b`: insertions, deletions, substitutions and swaps of two
neighbouring letters (optimal string alignment), so :pixle is one edit from :pixel."
  (let [la (length a) lb (length b)
        d {}]
    (for [i 0 la] (tset d i {0 i}))
    (for [j 0 lb] (tset (. d 0) j j))
    (for [i 1 la]
      (for [j 1 lb]
        (let [cost (if (= (a:sub i i) (b:sub j j)) 0 1)
              best (math.min (+ (. d (- i 1) j) 1) (+ (. d i (- j 1)) 1)
                             (+ (. d (- i 1) (- j 1)) cost))]
          (tset (. d i) j
                (if (and (> i 1) (> j 1) (= (a:sub i i) (b:sub (- j 1) (- j 1)))
                         (= (a:sub (- i 1) (- i 1)) (b:sub j j)))
                    (math.min best (+ (. d (- i 2) (- j 2)) 1))
                    best)))))
    (. d la lb)))

{: valid-utf8? : edit-distance : first-invalid-byte : escape : quote-string : keyword : name?
 : printable : max-shown}

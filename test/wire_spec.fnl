;; tier: fast
;; The wire format between the scene worker and the player (src/util/wire.fnl): exact
;; round trips of plain data (doubles bit for bit), deterministic bytes, the encoder's
;; refusals naming the path, and a strict decoder that answers every malformed input
;; (truncated, mutated, lying counts, too deep, duplicate keys) with nil and
;; 'malformed data: ...', never an error.

(local ffi (require :ffi))
(local wire (require :src.util.wire))

(fn round-trip [value]
  (let [(bytes err) (wire.encode value)]
    (assert.is_nil err)
    (wire.decode bytes)))

(fn build [strings numbers ops]
  ;; Wire bytes made by hand: a list of strings, a list of numbers and the op string.
  (let [arr (ffi.new "double[?]" (length numbers))]
    (each [i x (ipairs numbers)] (tset arr (- i 1) x))
    (.. "SDW1 " (length strings) " " (length numbers) " " (length ops) "\n"
        (table.concat (icollect [_ s (ipairs strings)] (.. (length s) ":" s)))
        (ffi.string arr (* 8 (length numbers))) ops)))

(fn refused [pattern s ?limits]
  ;; Decoding `s` gives nil and a 'malformed data: ' message matching `pattern`.
  (let [(v msg) (wire.decode s ?limits)]
    (assert.is_nil v)
    (assert.is_string msg)
    (assert.truthy (msg:find "^malformed data: ") msg)
    (assert.truthy (msg:find pattern) msg)
    msg))

(local sample
  {:name "sample\0with\nbytes"
   :objects [{:kind "sphere" :pos [1 -2.5 3] :radius 0.5 :mirror true}
             {:kind "box" :size [] :tags ["a" "a" "é"] :hidden false}]
   :count 2
   7 "seven"})

(describe "wire round trips"
  (fn []
    (it "gives back nested maps, lists, empty tables and every kind of string"
      (fn []
        (let [value {:a {:b {:c [1 [2 [3 {}]]]}}
                     :empty {}
                     :strings ["" "nul\0inside" "new\nline" "UTF-8: Größe ✓ 🌀" "\255\254"]
                     :flags [true false true]
                     -3 "negative key"
                     0 "zero key"
                     1e15 "big key"}]
          (assert.are.same value (round-trip value))
          (assert.are.same sample (round-trip sample)))))

    (it "keeps every double exactly, -0.0, subnormals, infinities and NaN included"
      (fn []
        (let [xs [0.0 -0.0 (+ 0.1 0.2) 1e-310 4.9e-324 math.huge (- math.huge) (/ 0 0)
                  (^ 2 53) (+ (^ 2 53) 2) (- (^ 2 53)) (* 1.5 (^ 2 1023)) math.pi -1]
              back (round-trip xs)]
          (assert.are.equal (length xs) (length back))
          (for [i 1 (length xs)]
            (let [x (. xs i) y (. back i)]
              (if (not= x x) (assert.are_not.equal y y)
                  (assert.are.equal x y))))
          (assert.are.equal (- math.huge) (/ 1 (. back 2)))
          (assert.are.equal math.huge (/ 1 (. back 1)))
          (assert.are.equal (+ 0.1 0.2) (. back 3))
          (assert.are_not.equal 0.3 (. back 3))
          (assert.are.equal 1e-310 (. back 4))
          (assert.are.equal 9007199254740992 (. back 9)))))

    (it "sends a value that is not a table, and the empty table as an empty list"
      (fn []
        (assert.are.equal "text" (round-trip "text"))
        (assert.are.equal 42 (round-trip 42))
        (assert.are.equal false (round-trip false))
        (assert.are.equal "SDW1 0 0 2\n[}" (wire.encode {}))
        (assert.are.same {} (round-trip {}))))

    (it "sends a table with holes as a map with integer keys"
      (fn []
        (let [holes {1 true 3 true}
              bytes (wire.encode holes)]
          (assert.are.equal "{ntnt}" (bytes:sub -6))
          (assert.are.same holes (wire.decode bytes)))))

    (it "gives the same bytes for the same data, whatever the insertion order"
      (fn []
        (let [a {} b {}]
          (each [_ k (ipairs [:zeta :alpha 3 :mid -1 :beta 10])] (tset a k k))
          (each [_ k (ipairs [10 :beta -1 :mid 3 :alpha :zeta])] (tset b k k))
          (assert.are.equal (wire.encode a) (wire.encode b))
          (assert.are.equal (wire.encode sample) (wire.encode (round-trip sample))))))

    (it "sends each distinct string once"
      (fn []
        (let [bytes (wire.encode [:kind :kind {:kind :kind}])]
          (assert.truthy (bytes:find "^SDW1 1 4 8\n4:kind")))))

    (it "frames a message with its length"
      (fn []
        (assert.are.equal "5\nhello" (wire.frame "hello"))
        (assert.are.equal "0\n" (wire.frame ""))
        (assert.are.same {:max-depth 100 :max-bytes (* 256 1024 1024)} wire.limits)))))

(describe "wire.encode refusals"
  (fn []
    (it "refuses functions, threads and userdata, naming the path"
      (fn []
        (assert.are.same [nil "cannot send a function at objects.2.pos"]
                         [(wire.encode {:objects [{} {:pos print}]})])
        (assert.are.same [nil "cannot send a thread at co"]
                         [(wire.encode {:co (coroutine.create #nil)})])
        (assert.are.same [nil "cannot send a userdata at the top"]
                         [(wire.encode io.stdout)])
        (assert.are.same [nil "cannot send a nil at the top"] [(wire.encode nil)])))

    (it "refuses keys that are not strings or integers"
      (fn []
        (assert.are.same [nil "cannot send the key 1.5 at a (keys are strings or integers)"]
                         [(wire.encode {:a {1.5 :x}})])
        (assert.are.same [nil "cannot send the key inf at the top (keys are strings or integers)"]
                         [(wire.encode {math.huge 1})])
        (assert.are.same [nil "cannot send a boolean key at the top (keys are strings or integers)"]
                         [(wire.encode {true 1})])
        (assert.are.same [nil "cannot send a table key at the top (keys are strings or integers)"]
                         [(wire.encode {[{} 1] 1})])))

    (it "refuses a cycle and tables nested too deep"
      (fn []
        (let [cycle {:items []}]
          (table.insert cycle.items cycle)
          (let [(v msg) (wire.encode cycle)]
            (assert.is_nil v)
            (assert.truthy (msg:find "^nested deeper than 100 at items%.1%.items%.1%.") msg)))
        (var deep [])
        (for [_ 1 99] (set deep [deep]))
        (assert.is_string (wire.encode deep))
        (assert.are.same [nil "nested deeper than 100 at 1.1.1.1.1.1.1.1... (100 keys) ...1.1.1"]
                         [(wire.encode [deep])])
        (assert.are.same [nil "nested deeper than 2 at 1.1"]
                         [(wire.encode [[[]]] {:max-depth 2})])))))

(describe "wire.decode refusals"
  (fn []
    (let [small (wire.encode {:a [1 true "x\n"] :b {} 3 false})]

      (it "refuses every truncation of an encoding"
        (fn []
          (for [n 0 (- (length small) 1)]
            (refused "" (small:sub 1 n)))))

      (it "answers every single-byte change with a value or a message, never an error"
        (fn []
          (for [i 1 (length small)]
            (for [b 0 255]
              (let [s (.. (small:sub 1 (- i 1)) (string.char b) (small:sub (+ i 1)))
                    (ok? v msg) (pcall wire.decode s)]
                (assert.is_true ok?)
                (when (= v nil)
                  (assert.is_string msg)
                  (assert.truthy (msg:find "^malformed data: ") msg)
                  (assert.falsy (msg:find "unexpected error" 1 true) msg)))))))

      (it "refuses trailing bytes, whatever they are"
        (fn []
          (refused "" (.. small "x"))
          (refused "" (.. small "\n"))
          (refused "trailing bytes after the value, from op 2"
                   (.. (build [] [] "tt")))
          (refused "trailing bytes" (build [] [] "[}}"))))

      (it "refuses huge header counts at once"
        (fn []
          (refused "the header counts %(999999999999 strings, 0 numbers, 0 ops%) need more"
                   "SDW1 999999999999 0 0\n")
          (refused "need more" "SDW1 0 999999999999999 1\nn")
          (refused "bad header" "SDW1 0 0 9999999999999999\n")
          (refused "need more" (.. "SDW1 0 0 1000000\n" (string.rep "t" 999999)))))

      (it "refuses a bad header and counts that do not match the length"
        (fn []
          (refused "expected a string, got a number" 42)
          (refused "bad header" "")
          (refused "bad header" "SDW2 0 0 1\nt")
          (refused "bad header" "SDW1 0 0 01\nt")
          (refused "bad header" "SDW1 0 0 1 \nt")
          (refused "bad header" "SDW1 0 0 -1\nt")
          (refused "bad length of string 1" "SDW1 1 0 1\nx:t")
          (refused "string 1 %(5 bytes at byte 14%) runs past the end" "SDW1 1 0 1\n5:abt")
          (refused "do not match the length" "SDW1 0 0 1\nxt")
          (refused "more numbers used than the 0 sent" "SDW1 0 0 1\nn")
          (refused "1 of the 2 numbers left unused" (build [] [1 2] "n"))
          (refused "more than the limit of 10" small {:max-bytes 10})))

      (it "refuses unknown ops, unbalanced ends and unfinished values"
        (fn []
          (refused "unknown op byte 120 at op 2 %(byte 13%)" (build [] [] "[x}"))
          (refused "unbalanced } at op 1" (build [] [] "}"))
          (refused "no value" (build [] [] ""))
          (refused "2 lists or maps left open" (build [] [] "[["))
          (refused "a map ends after a key without its value" (build ["k"] [1] "{s}"))))

      (it "refuses keys that are not strings or integers, and duplicate keys"
        (fn []
          (refused "a map key is not a string or an integer %(nan%)" (build [] [(/ 0 0) 1] "{nn}"))
          (refused "a map key is not a string or an integer %(1%.5%)" (build [] [1.5 1] "{nn}"))
          (refused "a map key is not a string or an integer %(inf%)" (build [] [math.huge 1] "{nn}"))
          (refused "a map key is not a string or an integer %(a boolean%)" (build [] [] "{tt}"))
          (refused "a map key is not a string or an integer %(a table%)" (build [] [] "{[}t}"))
          (refused "duplicate key \"k\" at op 4" (build ["k"] [1 1 1 2] "{snsn}"))
          (refused "duplicate key \"2\" at op 4" (build [] [2 1 2 1] "{nnnn}"))
          (assert.are.same {:k 1 2 true} (wire.decode (build ["k"] [1 1 2] "{snnt}")))))

      (it "reads a list of numbers in one op, and refuses a count past the numbers sent"
        (fn []
          (assert.are.same {:pos [1 2 3] :empty []} (wire.decode (wire.encode {:pos [1 2 3] :empty []})))
          (assert.are.same [[0.5 -1] [true 2]] (wire.decode (wire.encode [[0.5 -1] [true 2]])))
          (assert.are.same [1 2] (wire.decode (build [] [2 1 2] "v")))
          (assert.are.same [] (wire.decode (build [] [0] "v")))
          (refused "a list of 3 numbers, with 2 left, at op 1" (build [] [3 1 2] "v"))
          (refused "a list of 1%.5 numbers" (build [] [1.5 1 2] "v"))
          (refused "a list of %-1 numbers" (build [] [-1] "v"))
          (refused "trailing bytes after the value, from op 2" (build [] [1 7] "vt"))))

      (it "refuses string indexes out of range or not integers"
        (fn []
          (refused "string index 2 is not one of 1%.%.1" (build ["a"] [2] "s"))
          (refused "string index 0 is not one of" (build ["a"] [0] "s"))
          (refused "string index 1%.5 is not one of" (build ["a" "b"] [1.5] "s"))
          (refused "string index nan is not one of" (build ["a"] [(/ 0 0)] "s"))
          (refused "string index 1 is not one of 1%.%.0" (build [] [1] "s"))
          (assert.are.equal "b" (wire.decode (build ["a" "b"] [2] "s")))))

      (it "refuses data nested past the depth limit"
        (fn []
          (let [nest (fn [n] (build [] [] (.. (string.rep "[" n) (string.rep "}" n))))]
            (assert.is_table (wire.decode (nest 100)))
            (refused "nested deeper than 100 at op 101" (nest 101))
            (refused "nested deeper than 100" (.. "SDW1 0 0 1000000\n" (string.rep "[" 1000000)))
            (refused "nested deeper than 3 at op 4" (nest 4) {:max-depth 3})
            (assert.is_table (wire.decode (nest 3) {:max-depth 3}))))))))

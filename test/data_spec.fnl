;; tier: fast
;; Scene files of plain data (src/scene/data.fnl): read without the compiler, the same
;; values as Fennel's, hostile text refused or sent to the compiler, large files within
;; their limits; and the step budget of scenes made by loops (src/scene/sandbox.fnl).
(local fennel (require :fennel))
(local data (require :src.scene.data))
(local scene (require :src.scene.load))
(local sandbox (require :src.scene.sandbox))
(local worker (require :src.scene.worker))

(fn pack [...] (doto [...] (tset :n (select :# ...))))

(fn read-all [path]
  (with-open [f (assert (io.open path :rb))] (f:read :*a)))

(fn write-file [path text]
  (with-open [f (assert (io.open path :wb))] (f:write text)))

(fn plain [v]
  ;; `v` without metatables (Fennel's parser marks its tables), for comparing.
  (if (= (type v) :table) (collect [k x (pairs v)] (plain k) (plain x)) v))

(fn fennel-value [text]
  "What Fennel's parser reads from `text` (one form)."
  (let [(ok? v) ((fennel.parser (fennel.string-stream text) "t.fnl"))]
    (assert ok? text)
    (plain v)))

(fn sphere-lines [n]
  (fcollect [i 1 n]
    (string.format "  {:kind :sphere :radius %.3f :pos [%.3f %.3f %.3f] :color [%.3f %.3f %.3f]}"
                   (+ 0.2 (* 0.05 (% i 7))) (- (% (* i 0.37) 100) 50) (- (% (* i 1.7) 100) 50)
                   (% (* i 3.1) 40) (/ (% i 10) 10) (/ (% i 13) 13) (/ (% i 17) 17))))

(fn spheres-file [n]
  (.. "{:camera {:pos [0 -60 20] :pitch -15}\n :objects [\n"
      (table.concat (sphere-lines n) "\n") "]}\n"))

(fn code-version [text]
  ;; The same scene made code: a form before it on its first line, so the table
  ;; stays the last form (the one the loader takes lines from) on the same lines.
  (.. "(local x 1) " text))

(describe "plain data: the reader"
  (fn []
    (it "reads what Fennel's parser reads: numbers, strings, keywords, booleans, tables"
      (fn []
        (each [_ text (ipairs ["{:a 1 :b -2.5 :c 1e3 :d -1.5E-3 :e .5 :f -.25 :g 0.1 :h 123456789012345678}"
                               "[1 [2 [3 []]] {} {:x true :y false}]"
                               "{\"key with space\" \"value\" 1 :one 2.5 :two-and-a-half true :yes}"
                               "{:esc \"a\\\"b\\\\c\\nd\\te\\065\\0659\\255\" :multi \"two\nlines\"}"
                               "{:kw-chars [:a.b :a:b :a?b! :<=> :ünï :+ :-]}"
                               "; a comment\n{:a [1 2 3] ; another\n :b {:c :d}}\n;; the end"
                               "{:ws\t[1\r\n2\f3\v4]}"
                               "{:big 1e400 :small 1e-400 :neg -0 :digits 123456789012345678901234567890}"])]
          (let [(v why) (data.read text)]
            (assert.is_not_nil v (.. text ": " (tostring why)))
            (assert.are.same (fennel-value text) (plain v))))))

    (it "reads numbers bit for bit as tonumber does (digits, points, signs, exponents)"
      (fn []
        ;; A fixed generator: 20,000 numbers of 1 to 20 digits, the point anywhere,
        ;; some negative, some with an exponent (those take the token path).
        (var seed 7)
        (fn rnd [n]
          (set seed (% (+ (* seed 1103515245) 12345) 2147483648))
          (% (math.floor (/ seed 65536)) n))
        (let [words (fcollect [_ 1 20000]
                      (let [digits (fcollect [_ 1 (+ 1 (rnd 20))] (tostring (rnd 10)))
                            at (rnd (+ 2 (length digits)))]
                        (when (<= at (length digits)) (table.insert digits (+ at 1) "."))
                        (.. (if (= 0 (rnd 3)) "-" "") (table.concat digits)
                            (if (= 0 (rnd 10)) (.. "e" (- (rnd 40) 20)) ""))))
              v (assert (data.read (.. "[" (table.concat words " ") "]")))]
          (each [i w (ipairs words)]
            (let [want (tonumber w)]
              (assert.is_true (and (= want (. v i)) (= (/ 1 want) (/ 1 (. v i))))
                              (.. w ": " (string.format "%.17g" (. v i)) ", tonumber "
                                  (string.format "%.17g" want))))))))

    (it "reads every data file of scenes/ and test/corpus/ as Fennel's parser does"
      (fn []
        (var n 0)
        (with-open [ls (io.popen "ls scenes/*.fnl test/corpus/*.fnl")]
          (each [path (ls:lines)]
            (let [text (read-all path)
                  v (data.read text)]
              ;; Files Fennel cannot parse (the corpus has some) are never data.
              (when (not= nil v)
                (set n (+ n 1))
                (assert.are.same (fennel-value text) (plain v) path)))))
        (assert.is_true (> n 50) (.. n " data files"))))

    (it "leaves to Fennel whatever is not plain data, saying why"
      (fn []
        (each [text why (pairs {"{:a (+ 1 2)}" "a list (...): code"
                                "{:a math.pi}" "the symbol math.pi"
                                "{:a nil}" "nil"
                                "{:a 0x10}" "the symbol 0x10"
                                "{:a 1_000}" "the symbol 1_000"
                                "{:a .inf}" "the symbol .inf"
                                "{:a \"\\x41\"}" "a string escape this reader leaves to Fennel"
                                "{:a \"\\z\"}" "a string escape this reader leaves to Fennel"
                                "{:a \"\\256\"}" "a string escape past \\255"
                                "{:a \"unterminated}" "an unterminated string"
                                "{:a [1 2}" "a mismatched closing bracket"
                                "{:a [1 2]" "an unclosed bracket"
                                "{:a}" "a table with an odd number of forms"
                                "{:a 1 :a 2}" "a key given twice"
                                "{[1] 2}" "a table as a key"
                                "{:a [1][2]}" "two forms with no space between them"
                                "{:a 1} {:b 2}" "more than one form"
                                "" "no form"
                                "{: a}" "a colon that is not a keyword"
                                "{:a 'x}" "the character '"
                                "{:a #(+ 1)}" "the symbol #"})]
          (let [(v kind reason) (data.read text)]
            (assert.is_nil v text)
            (assert.are.equal :not-data kind text)
            (assert.are.equal why reason text)))))

    (it "refuses nesting past its limit at the bracket that passes it"
      (fn []
        (let [text (.. "{:a\n" (string.rep "[" 200) (string.rep "]" 200) "}")
              (v kind why pos) (data.read text {:max-depth 100})]
          (assert.is_nil v)
          (assert.are.same [:refused :too-deep 104] [kind why pos])
          (assert.are.equal 2 (data.line-at text pos)))))

    (it "refuses data past its memory limit (empty tables, two bytes each)"
      (fn []
        (let [text (.. "[" (string.rep "[] " 2000000) "]")
              (v kind why) (data.read text {:max-memory-mb 16})]
          (assert.is_nil v)
          (assert.are.equal :refused kind)
          (assert.are.equal "the file's data takes more than 16 MB of memory" why))))

    (it "gives tables Fennel's source fields when asked, for the loader's lines"
      (fn []
        (let [v (data.read "{:a 1\n :b [1\n 2]\n :c {:d\n 3}}" {:positions? true})]
          (assert.are.equal 1 (. (fennel.ast-source v) :line))
          (assert.are.equal 2 (. (fennel.ast-source v.b) :line))
          (assert.are.equal 4 (. (fennel.ast-source v.c) :line)))))))

(describe "plain data: the loader"
  (fn []
    (it "gives the same scene as the compiler for every data scene in scenes/"
      (fn []
        (var n 0)
        (each [_ name (ipairs [:flat :flower :lighting :seed :spheres :twisted-tower])]
          (let [path (.. "scenes/" name ".fnl")
                text (read-all path)]
            (when (data.read text)
              (set n (+ n 1))
              (assert.are.same (assert (scene.load-string (code-version text) path))
                               (assert (scene.load-string text path))))))
        (assert.are.equal 6 n)))

    (it "gives the compiler's messages, lines included, for bad data"
      (fn []
        (each [_ text (ipairs ["{:objects [{:kind :sphere}\n {:kind :boxx}]}"
                               "{:objects [{:kind :sphere :radius 1e999}]}"
                               "{:objects [{:kind :sphere\n :radius -1}]}"
                               "{:camera {:pos [0 0]}\n :objects []}"
                               "{:objects []\n :render {:hit-test :pixle}}"
                               "{:objects [\n {:kind :box\n  :size [1 -1 1]}]}"
                               "[1 2 3]"
                               "{:objects [] :name \"a\\nb\"}"])]
          (let [(_ from-data) (scene.load-string text "t.fnl")
                (_ from-code) (scene.load-string (code-version text) "t.fnl")]
            (assert.is_not_nil from-data text)
            (assert.are.equal from-code from-data)))))

    (it "sends code and unsure text to the compiler, as before"
      (fn []
        (let [s (assert (scene.load-string "{:objects [] :name (.. :a :b)}" "t.fnl"))]
          (assert.are.equal "ab" s.name))
        (let [(_ err) (scene.load-string "{:objects [] :name \"unterminated}" "t.fnl")]
          (assert.truthy (err:find "^t.fnl:1:") err))))

    (it "refuses text that is not UTF-8, small or large"
      (fn []
        (let [(_ small) (scene.load-string "{:objects []\n :name \"\255\"}" "t.fnl")
              (_ large) (scene.load-string (.. (spheres-file 7000) "{:name \"\255\"}") "t.fnl")]
          (assert.are.equal "t.fnl:2: the file is not UTF-8 text (byte 0xFF at column 9); scene files are Fennel source"
                            small)
          (assert.truthy (large:find "^t.fnl:7003: the file is not UTF%-8 text %(byte 0xFF") large))))

    (it "refuses a large file whose tables take too much memory"
      (fn []
        (let [memory sandbox.limits.data-memory-mb]
          (set sandbox.limits.data-memory-mb 16)
          (let [(_ err) (scene.load-string (.. "{:objects []\n :x [" (string.rep "[] " 1000000) "]}") "t.fnl")]
            (set sandbox.limits.data-memory-mb memory)
            (assert.truthy (err:find "^t.fnl:2: the file's data takes more than 16 MB of memory$") err)))))

    (it "refuses nesting too deep in a large file with the sandbox's message"
      (fn []
        (let [(_ err) (scene.load-string (.. "{:objects [\n" (table.concat (sphere-lines 7000) "\n")
                                             "]\n :deep " (string.rep "[" 150) (string.rep "]" 150) "}")
                                         "t.fnl")]
          (assert.are.equal "t.fnl:7002: the scene nests deeper than 100 levels of brackets" err))))

    (it "loads 10,000 spheres written out (870 KB, over the limit of code), with lines in messages"
      (fn []
        (let [text (spheres-file 10000)
              s (assert (scene.load-string text "big.fnl"))]
          (assert.is_true (> (length text) sandbox.limits.file-bytes))
          (assert.are.equal 10000 (length s.objects))
          (assert.are.same [-49.63 -48.3 3.1] (. s.objects 1 :pos))
          (assert.are.equal 0.25 (. s.objects 1 :radius)))
        ;; One bad radius on line 9002 (object 9000).
        (let [lines (sphere-lines 10000)]
          (tset lines 9000 "  {:kind :sphere :radius -1}")
          (let [(_ err) (scene.load-string (.. "{:objects [\n" (table.concat lines "\n") "]}") "big.fnl")]
            (assert.are.equal "big.fnl:9001: objects[9000].radius: must be a positive number from 1e-6 to 1e7, got -1"
                              err)))))

    (it "needs no worker for plain data"
      (fn []
        ;; A worker that cannot start: a data file loads all the same, code does not.
        (worker.kill!)
        (worker.set-command! ["false"])
        (let [s (worker.load-source (spheres-file 3) "data.fnl")
              (_ err) (worker.load-source (code-version (spheres-file 3)) "code.fnl")]
          (worker.set-command! nil)
          (assert.are.equal 3 (length (. (assert s) :objects)))
          (assert.are.equal "code.fnl: the scene worker did not start (false): it ended at once" err))))))

(describe "scenes made by loops: the step budget"
  (fn []
    (fn with-limits [changes f]
      (let [saved (collect [k (pairs changes)] k (. sandbox.limits k))]
        (each [k v (pairs changes)] (tset sandbox.limits k v))
        (let [results (pack (pcall f))]
          (each [k v (pairs saved)] (tset sandbox.limits k v))
          (assert (. results 1) (. results 2))
          ((or table.unpack _G.unpack) results 2 results.n))))

    (it "grows with what a loop builds: 100,000 spheres on that alone, so 1,000,000 fit the same way"
      (fn []
        ;; With no steps before the scene has built anything, 100,000 spheres made by
        ;; a loop (99 steps and about 340 bytes each) load on the steps their own
        ;; data earns. Both grow with the count: ten times the spheres, ten times the
        ;; memory (342 MB, within the 512 MB limit) and ten times the steps.
        (let [text (read-all "test/fixtures/spheres-100000.fnl")
              s (with-limits {:steps 1000}
                  #(assert (scene.load-string text "spheres-100000.fnl")))]
          (assert.are.equal 100000 (length s.objects))
          ;; Without the growth the same loop is stopped.
          (let [(_ err) (with-limits {:steps 1000000 :steps-per-kb 0}
                          #(scene.load-string text "spheres-100000.fnl"))]
            (assert.are.equal "spheres-100000.fnl: the scene ran for more than 1 million steps and was stopped (an endless loop?)"
                              err)))
        ;; What one sphere of that loop takes, measured on its full run; a million of
        ;; them must fit the memory limit and the steps their memory earns.
        (let [text (read-all "test/fixtures/spheres-100000.fnl")
              real-run sandbox.run
              seen {}]
          (set sandbox.run (fn [...]
                             (collectgarbage)
                             (let [before (collectgarbage :count)
                                   (ok? value used) (real-run ...)]
                               (set seen.kb (- (collectgarbage :count) before))
                               (set seen.steps used)
                               (values ok? value used))))
          (let [(ok? err) (pcall scene.load-string text "spheres-100000.fnl")]
            (set sandbox.run real-run)
            (assert ok? err))
          (let [kb (* 10 seen.kb)                 ; a million spheres
                steps (* 10 seen.steps)
                limits sandbox.limits]
            (assert.is_true (< kb (* 1024 limits.memory-mb)) (.. kb " KB"))
            (assert.is_true (< steps (+ limits.steps (* limits.steps-per-kb kb)))
                            (.. steps " steps for " kb " KB"))))
        (assert.are.equal 1000000 scene.limits.max-objects)))

    (it "still stops endless loops, those that build garbage and those that build too slowly"
      (fn []
        (each [text why (pairs {"(while true) {:objects []}" "steps"
                                "(while true (local x [1 2 3])) {:objects []}" "steps"
                                ;; One small table every 10,000 steps: far fewer bytes
                                ;; than steps.
                                "(local t []) (for [i 1 1e12] (when (= 0 (% i 2000)) (table.insert t i))) {:objects []}" "steps"})]
          (let [(_ err) (with-limits {:steps 2000000}
                          #(scene.load-string text "t.fnl"))]
            ;; (The budget grows with the memory the scene holds, and garbage comes
            ;; and goes with the collector: 2 million steps or some more.)
            (assert.truthy (err:find "^t.fnl: the scene ran for more than %d+ million steps and was stopped %(an endless loop%?%)$")
                           (.. text ": " err))))
        (let [(_ err) (with-limits {:memory-mb 32}
                        #(scene.load-string "(local t []) (while true (table.insert t [1 2 3])) {:objects []}" "t.fnl"))]
          (assert.are.equal "t.fnl: the scene built more than 32 MB of data and was stopped" err))))))

;; The sandbox around scene files (src/scene/sandbox.fnl) and the safe text of messages
;; (src/util/text.fnl): what a hostile file cannot do, and that nothing it tries outlives
;; its own load.
(local fennel (require :fennel))
(local scene (require :src.scene.load))
(local sandbox (require :src.scene.sandbox))
(local text (require :src.util.text))

(fn write-file [path data]
  (with-open [f (assert (io.open path :wb))] (f:write data)))

(fn global-scope []
  (let [s (fennel.scope)] (or s.parent s)))

(describe "sandbox: the compiler's shared state"
  (fn []
    (it "is untouched by hostile scenes: a fresh module compiled afterwards behaves"
      (fn []
        (let [g (global-scope)
              local-before (. g.specials :local)
              trace "test/out/sandbox-trace"]
          (os.remove trace)
          (each [_ src (ipairs [(.. "{(do (eval-compiler (tset _SPECIALS :local (fn [] "
                                    "(os.execute \"touch " trace "\")))) :environment) [1 1 1]"
                                    " :objects []}")
                                "{(eval-compiler (set _G.hacked true)) 1 :objects []}"
                                "{:objects [] :name (macrodebug (local x 1) true)}"
                                "(let [t {(lua \"_G.hacked = true\") 1}] {:objects []})"])]
            (let [(s err) (scene.load-string src "hostile.fnl")]
              (assert.is_nil s)
              (assert.truthy (err:find "is not allowed" 1 true) err)))
          (assert.are.equal local-before (. g.specials :local))
          (assert.is_nil (rawget _G :hacked))
          ;; A module compiled now, in the same process, with the full environment.
          (let [value (fennel.eval "(local x 20) (let [y 22] (+ x y))"
                                   {:env _G :allowedGlobals false})]
            (assert.are.equal 42 value))
          (assert.is_nil (io.open trace) "the hostile scene's code ran"))))

    (it "is restored, and the scene refused, if a compile ever changed it"
      (fn []
        ;; Make the compiler itself misbehave during one compile: the second layer of
        ;; defence (the allowlist is the first) must put things back.
        (let [g (global-scope)
              real-compile fennel.compile-string
              real-local (. g.specials :local)]
          (set fennel.compile-string
               (fn [...]
                 (tset g.specials :local (fn [] (error "hijacked")))
                 (tset g.macros :evil (fn [] nil))
                 (real-compile ...)))
          (let [(s err) (scene.load-string "{:objects []}" "t.fnl")]
            (set fennel.compile-string real-compile)
            (assert.is_nil s)
            (assert.are.equal "t.fnl: the scene changed the Fennel compiler and was refused" err))
          (assert.are.equal real-local (. g.specials :local))
          (assert.is_nil (. g.macros :evil))
          (assert.are.equal real-compile fennel.compile-string))))

    (it "is not reachable: every special form and macro outside the allowlist is refused"
      (fn []
        (let [g (global-scope)
              names (doto (icollect [k (pairs g.specials)] k) table.sort)]
          (each [k (pairs g.macros)] (table.insert names k))
          (var refused 0)
          (each [_ name (ipairs names)]
            (let [(s err) (scene.load-string (.. "{(" name " x) 1 :objects []}") "t.fnl")]
              (when (and err (err:find "is not allowed" 1 true))
                (set refused (+ refused 1)))))
          (each [_ name (ipairs [:eval-compiler :macro :macros :lua :include :import-macros
                                 :require-macros :global :set-forcibly! :quote :macrodebug])]
            (let [(_ err) (scene.load-string (.. "{(" name " x) 1 :objects []}") "t.fnl")]
              (assert.truthy (and err (err:find "is not allowed" 1 true))
                             (.. name " in a key: " (tostring err)))))
          (assert.is_true (>= refused 14) (.. refused " forms refused")))))))

(describe "sandbox: the file before it is parsed"
  (fn []
    (it "refuses a file over 512 KB, reading no more than the limit"
      (fn []
        (let [path "test/out/sandbox-big.fnl"]
          (os.execute "mkdir -p test/out")
          (write-file path (.. "{:objects []}\n" (string.rep ";; padding\n" 100000)))
          (let [(s err) (scene.load-file path)]
            (os.remove path)
            (assert.is_nil s)
            (assert.are.equal (.. path ": the file is over 524288 bytes (512 KB), the most a scene file may have"
                                  "; make many objects with a loop, like (fcollect [i 1 n] {:kind :sphere ...})")
                              err)))))

    (it "refuses /dev/zero without reading it"
      (fn []
        (let [(s err) (scene.load-file "/dev/zero")]
          (assert.is_nil s)
          (assert.are.equal (.. "/dev/zero: the file is over 524288 bytes (512 KB), the most a scene file may have"
                                "; make many objects with a loop, like (fcollect [i 1 n] {:kind :sphere ...})")
                            err))))

    (it "says a directory is a directory"
      (fn []
        (let [(s err) (scene.load-file "scenes")]
          (assert.is_nil s)
          (assert.are.equal "scenes: cannot read the scene file: it is a directory" err))))

    (it "reads a file with a UTF-8 byte order mark"
      (fn []
        (let [s (assert (scene.load-string "\239\187\191{:objects [{:kind :sphere}]}" "bom.fnl"))]
          (assert.are.equal 1 (length s.objects)))))

    (it "measures nesting on the text, so 5000 brackets give the nesting message"
      (fn []
        (let [(_ err) (scene.load-string (.. "{:objects [] :name \"((((\" ; [[[[\n "
                                             (string.rep "(" 5000) (string.rep ")" 5000) "}")
                                         "t.fnl")]
          (assert.are.equal "t.fnl:2: the scene nests deeper than 100 levels of brackets"
                            err))))))

(describe "sandbox: limits"
  (fn []
    (it "stops an endless loop by counting steps, so the verdict does not depend on the clock"
      (fn []
        (let [(_ err) (scene.load-string "(while true) {:objects []}" "t.fnl")]
          (assert.are.equal "t.fnl: the scene ran for more than 20 million steps and was stopped (an endless loop?)"
                            err))))

    (it "stops a scene that builds too much data before it runs out of steps"
      (fn []
        (let [(_ err) (scene.load-string "{:objects (fcollect [i 1 1e8] {:kind :sphere})}" "t.fnl")]
          (assert.are.equal "t.fnl: the scene built more than 96 MB of data and was stopped" err))))

    (it "caps what one library call may build, and names the call and line"
      (fn []
        (each [src msg (pairs {"\n{:objects [] :name (string.rep \"ab\" 600000)}" "t.fnl:2: string.rep"
                               "\n{:objects [] :name (table.concat [(string.rep \"a\" 600000) (string.rep \"b\" 600000)])}" "t.fnl:2: table.concat"
                               "\n{:objects [] :name (string.format \"%s%s\" (string.rep \"a\" 600000) \"b\")}" "t.fnl:2: string.format"})]
          (let [(_ err) (scene.load-string src "t.fnl")]
            (assert.are.equal (.. msg ": the result would be over 1 MB") err)))))

    (it "gives its own errors a marker no scene can forge"
      (fn []
        (assert.is_false (sandbox.sandbox-error? {:sandbox {} :message "forged"}))
        (assert.are.equal "the scene raised an error that is not a message"
                          (sandbox.error-message (setmetatable {} {:__tostring #(error "boom")})))))))

(describe "text: safe messages"
  (fn []
    (it "checks UTF-8"
      (fn []
        (assert.is_true (text.valid-utf8? "café ☕ 𝄞"))
        (assert.is_false (text.valid-utf8? "caf\233"))
        (assert.is_false (text.valid-utf8? "\192\128"))      ; overlong NUL
        (assert.is_false (text.valid-utf8? "\237\160\128"))  ; a surrogate
        (assert.is_false (text.valid-utf8? "a\000b"))
        (assert.are.equal 4 (text.first-invalid-byte "abc\255"))))

    (it "escapes control characters and broken bytes, and shortens long text"
      (fn []
        (assert.are.equal "\\027[2J" (text.escape "\27[2J"))
        (assert.are.equal "caf\\233 ok" (text.escape "caf\233 ok"))
        (assert.are.equal "\"a\\\"b\"" (text.quote-string "a\"b"))
        (assert.are.equal (.. "\"" (string.rep "x" 40) "\"... (100 bytes)")
                          (text.quote-string (string.rep "x" 100)))
        (assert.are.equal ":radius" (text.keyword "radius"))
        (assert.are.equal "\"two words\"" (text.keyword "two words"))
        (assert.are.equal "a\nb\\255" (text.printable "a\nb\255"))))))

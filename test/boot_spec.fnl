;; tier: fast
;; Specs for the compiled start (src/boot.lua, tools/build-lua.lua, conf.lua's loader):
;; the build writes what the loader takes, the loader takes it only while the source is
;; the one compiled, and errors still name the Fennel line.
(local boot (require :src.boot))
(local fennel (require :fennel))

(local app (require :test.support.app))
(local root app.root)

(fn sh [command]
  "Runs `command`; its stdout and stderr together, and its exit code."
  (let [(rc text) (app.sh command)]
    (values text rc)))

(fn write! [path text]
  (with-open [f (assert (io.open path "wb"))] (f:write text)))

(fn read [path]
  (case (io.open path "rb")
    f (with-open [f f] (f:read "*a"))))

(fn game! []
  "A small game folder: this project's conf.lua and src/boot.lua, and a main.fnl that
prints where it came from; its path."
  (let [dir (: (io.popen "mktemp -d") :read "*l")]
    (os.execute (.. "mkdir -p " dir "/src && cp " root "/conf.lua " dir "/ && cp "
                    root "/src/boot.lua " dir "/src/"))
    (write! (.. dir "/src/said.fnl") "{:from \"source\"}\n")
    (write! (.. dir "/main.fnl")
            ";; line 1\n(print (. (require :src.said) :from))\n(print (select 2 (pcall require :src.boom)))\n(os.exit 0)\n")
    ;; Raises on its line 3 when loaded: its message must name src/boom.fnl:3 (not the
    ;; module's last form, which would be a tail call and lose its position).
    (write! (.. dir "/src/boom.fnl") ";; line 1\n(local x 1)\n(error (.. \"boom \" x))\n{}\n")
    dir))

(fn build! [dir]
  (sh (.. "cd " dir " && luajit " root "/tools/build-lua.lua")))

(fn run-love [dir]
  ;; --help: conf.lua opens no window for it; this main.fnl ignores the arguments.
  (sh (.. "cd " dir " && SDL_VIDEODRIVER=offscreen timeout 300 love . --help")))

(describe "boot: the digest"
  (fn []
    (it "is 32-bit FNV-1a (the published test vectors)"
      (fn []
        (assert.are.equal "811c9dc5" (boot.digest ""))
        (assert.are.equal "e40c292c" (boot.digest "a"))
        (assert.are.equal "bf9cf968" (boot.digest "foobar"))))

    (it "tells a one-character edit apart"
      (fn []
        (assert.are_not.equal (boot.digest "(+ 1 2)") (boot.digest "(+ 1 3)"))))))

(describe "boot: fresh"
  (fn []
    (let [source "(local x 1)\n{: x}\n"
          compiled (boot.compile fennel source "src/x.fnl")]
      (it "keeps line N of the Lua on line N of the Fennel"
        (fn []
          (assert.truthy (compiled:find "^%-%-%[%[fnl %x+ [%d.]+%]%]"))
          (let [plain (fennel.compileString source {:filename "src/x.fnl" :correlate true})]
            (assert.are.equal (select 2 (plain:gsub "\n" ""))
                              (select 2 (compiled:gsub "\n" ""))))))

      (it "takes the compiled text made from this very source, by any Fennel version"
        (fn []
          (assert.are.equal compiled (boot.fresh compiled source))
          (assert.are.equal compiled (boot.fresh compiled source fennel.version))
          (assert.is_nil (boot.fresh compiled source "0.0.1"))))

      (it "refuses an edited source, a missing file and a file without a key"
        (fn []
          (assert.is_nil (boot.fresh compiled (.. source " ")))
          (assert.is_nil (boot.fresh nil source))
          (assert.is_nil (boot.fresh "return {}" source)))))))

(describe "the build and LÖVE's loader"
  (fn []
    (it "compiles what changed, removes what is gone, and fails on a broken module"
      (fn []
        (let [dir (game!)
              (out rc) (build! dir)]
          (assert.are.equal 0 rc out)
          (assert.truthy (out:find "3 of 3 modules compiled" 1 true) out)
          (assert.truthy (read (.. dir "/build/lua/src/said.lua")))
          (let [(again rc2) (build! dir)]
            (assert.are.equal 0 rc2)
            (assert.truthy (again:find "0 of 3 modules compiled" 1 true) again))
          (write! (.. dir "/src/extra.fnl") "(+ 1\n")
          (let [(broken rc3) (build! dir)]
            (assert.are.equal 1 rc3)
            (assert.truthy (broken:find "src/extra.fnl:2" 1 true) broken)
            (assert.is_nil (read (.. dir "/build/lua/src/extra.lua"))))
          (os.remove (.. dir "/src/extra.fnl"))
          (os.remove (.. dir "/src/said.fnl"))
          (build! dir)
          (assert.is_nil (read (.. dir "/build/lua/src/said.lua")))
          (os.execute (.. "rm -rf " dir)))))

    (it "runs the compiled Lua, and the source once it is edited"
      (fn []
        (let [dir (game!)
              compiled (.. dir "/build/lua/src/said.lua")]
          (build! dir)
          ;; Mark the build's text, key kept: LÖVE must run this file, not compile.
          (write! compiled (: (read compiled) :gsub "\"source\"" "\"build\""))
          (let [(out rc) (run-love dir)]
            (assert.are.equal 0 rc out)
            (assert.truthy (out:find "build" 1 true) out))
          (write! (.. dir "/src/said.fnl") "{:from \"edited source\"}\n")
          (let [(out rc) (run-love dir)]
            (assert.are.equal 0 rc out)
            (assert.truthy (out:find "edited source" 1 true) out))
          (os.execute (.. "rm -rf " dir)))))

    (it "names the Fennel file and line of an error raised by compiled code"
      (fn []
        (let [dir (game!)]
          (build! dir)
          (assert.truthy (: (read (.. dir "/build/lua/src/boom.lua")) :find "boom" 1 true))
          (let [(out) (run-love dir)]
            (assert.truthy (out:find "src/boom.fnl:3: boom 1" 1 true) out))
          (os.execute (.. "rm -rf " dir)))))))

;; The memory a large file of plain data takes in the process that reads it (the
;; app's own: src/scene/data.fnl runs there, without the worker's limits) (issue 43).
;; A refused file's message used to read the whole file again with a metatable of
;; source positions on every table, for the line: 1.9 million `{:kind :sphere}`
;; (30 MB) peaked at 1.1 GB to say there were too many, 3.5 million `[]` under an
;; unknown field at 1.2 GB. Now only the tables along the message's path are built
;; again. The files are generated here (test/out/, not committed); the peak is read
;; from /proc in a child process. Nothing here is timed.

(local data (require :src.scene.data))

(fn write-file [path parts]
  (with-open [f (assert (io.open path :wb))]
    (each [_ p (ipairs parts)] (f:write p))))

(fn load-in-child [path]
  "Load the scene file at `path` in a fresh LuaJIT: the message (or the object
count) and the peak resident memory in MB."
  (let [script "test/out/data-memory-load.fnl"]
    (write-file script
                ["(local load (require :src.scene.load))\n"
                 "(local (s err) (load.load-file (. arg 1)))\n"
                 "(local status (with-open [f (io.open \"/proc/self/status\")] (f:read :*a)))\n"
                 "(io.write (if s (.. (length s.objects) \" objects\") err) \"\\n\"\n"
                 "          (status:match \"VmHWM:%s*(%d+)\") \"\\n\")\n"])
    (let [out (with-open [p (io.popen (.. "luajit tools/fnl.lua " script " " path " 2>&1"))] (p:read :*a))
          (message kb) (out:match "^(.-)\n(%d+)\n$")]
      (assert message out)
      (values message (/ (tonumber kb) 1024)))))

(describe "a large file of plain data"
  (fn []
    (os.execute "mkdir -p test/out")

    (it "is read again only along the message's path for a refusal's line"
      (fn []
        (let [source (.. "{:name \"n\"\n :objects [{:kind :sphere}\n"
                         "  {:kind :box :pos [1 2 3]}\n  {:kind :sphere :radius [4]}]}")
              full (assert (data.read source {:positions? true}))
              sparse (assert (data.read source {:positions? true :path [:objects 3 :radius]}))
              fennel (require :fennel)]
          ;; Along the path: the tables and their lines, as the full read has them.
          (each [_ [t u] (ipairs [[sparse full] [sparse.objects full.objects]
                                  [(. sparse.objects 3) (. full.objects 3)]
                                  [(. sparse.objects 3 :radius) (. full.objects 3 :radius)]])]
            (assert.are.same (fennel.ast-source u) (fennel.ast-source t)))
          (assert.are.same [4] (. sparse.objects 3 :radius))
          (assert.are.equal "sphere" (. sparse.objects 3 :kind))
          ;; Off it: one shared empty table, no positions.
          (assert.are.equal (. sparse.objects 1) (. sparse.objects 2))
          (assert.are.same {} (. sparse.objects 1))
          (assert.is_nil (getmetatable (. sparse.objects 1)))
          (assert.are.equal "n" sparse.name))))

    (it "of 1.9 million objects is refused for its count without reading it all again"
      (fn []
        (let [path "test/out/data-memory-objects.fnl"]
          (write-file path ["{:objects [" (string.rep "{:kind :sphere} " 1900000) "]}\n"])
          (let [(message mb) (load-in-child path)]
            (os.remove path)
            (assert.are.equal (.. path ":1: objects: has 1900000 objects; at most 1000000 are"
                                  " allowed (remove 900000)")
                              message)
            ;; 1085 MB before (the whole file read again with positions), 530 after.
            (assert.is_true (< mb 800) (.. mb " MB"))))))

    (it "of 3.5 million empty tables under an unknown field is refused the same way"
      (fn []
        (let [path "test/out/data-memory-dense.fnl"]
          (write-file path ["{:objects []\n :junk [" (string.rep "[] " 3500000) "]}\n"])
          (let [(message mb) (load-in-child path)]
            (os.remove path)
            (assert.are.equal (.. path ":2: junk: unknown field; known fields: :camera"
                                  " :environment :light :lighting :name :objects :render")
                              message)
            ;; 1189 MB before, 591 after.
            (assert.is_true (< mb 850) (.. mb " MB"))))))))

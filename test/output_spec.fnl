;; Outputs (src/util/output.fnl and its four writers: --render's PNG, --record's
;; frames, --export-shader, the parameter save): written to a new file created
;; exclusively beside the target, renamed over it; links followed to their target and
;; kept; a directory, a FIFO, a dangling link or the scene itself refused, naming the
;; path, with nothing written and the scene intact.

(local output (require :src.util.output))
(local load (require :src.scene.load))
(local params (require :src.scene.params))

(local dir "test/out/output")

(fn write-file [path text]
  (with-open [f (assert (io.open path :wb))] (f:write text)))

(fn read-file [path]
  (with-open [f (assert (io.open path :rb))] (f:read :*a)))

(fn sh [command]
  (assert (os.execute command) command))

(fn link-target [path]
  ;; What the link at `path` points to, or nil when it is not a link.
  (with-open [p (io.popen (.. "readlink '" path "'"))]
    (let [s (p:read :*l)] (when (and s (not= s "")) s))))

(fn listing []
  (with-open [p (io.popen (.. "ls -A " dir))]
    (icollect [l (p:lines)] l)))

;; `love . ARGS` headless with a deadline (test/support/app.fnl): exit code and
;; combined output.
(local run (. (require :test.support.app) :love))

(local scene-text
  "{:name \"out\" :objects [{:kind :sphere :radius (param :r 1 {:min 0.5 :max 1.23456789})}]}\n")

(fn fresh! []
  ;; An empty folder with a scene, a link to it, a FIFO and a folder.
  (sh (.. "rm -rf " dir " && mkdir -p " dir))
  (write-file (.. dir "/scene.fnl") scene-text)
  (sh (.. "ln -s scene.fnl " dir "/link.png && ln -s scene.fnl " dir "/link.glsl"
          " && mkfifo " dir "/fifo.png && mkdir " dir "/folder.png")))

(describe "output.write!"
  (fn []
    (before_each fresh!)

    (it "writes a new file and replaces an existing one, leaving nothing beside it"
      (fn []
        (assert.is_true (output.write! (.. dir "/a.png") "one"))
        (assert.is_true (output.write! (.. dir "/a.png") "two"))
        (assert.are.equal "two" (read-file (.. dir "/a.png")))
        (assert.are.same ["a.png" "fifo.png" "folder.png" "link.glsl" "link.png" "scene.fnl"]
                         (doto (listing) table.sort))))

    (it "refuses a FIFO at once, without opening it"
      (fn []
        (assert.are.same [nil (.. "--out " dir "/fifo.png: is a FIFO; refusing to write to it")]
                         [(output.write! (.. dir "/fifo.png") "x" {:label (.. "--out " dir "/fifo.png")})])))

    (it "refuses a directory and a link to nothing"
      (fn []
        (assert.are.same [nil (.. dir "/folder.png: is a directory; refusing to write to it")]
                         [(output.write! (.. dir "/folder.png") "x")])
        (sh (.. "ln -s nowhere " dir "/dangling.png"))
        (assert.are.same [nil (.. dir "/dangling.png: is a symbolic link to nothing (or a loop of links);"
                                  " refusing to write through it")]
                         [(output.write! (.. dir "/dangling.png") "x")])
        (assert.are.equal "nowhere" (link-target (.. dir "/dangling.png")))))

    (it "refuses a protected file reached through a link, and the scene stays"
      (fn []
        (assert.are.same [nil (.. dir "/link.png: is the scene file " dir "/scene.fnl"
                                  " (after following links); choose another name")]
                         [(output.write! (.. dir "/link.png") "PNG" {:protect [(.. dir "/scene.fnl")]})])
        (assert.are.equal scene-text (read-file (.. dir "/scene.fnl")))))

    (it "writes into a link's target and keeps the link when it is not protected"
      (fn []
        (assert.is_true (output.write! (.. dir "/link.png") "new"))
        (assert.are.equal "scene.fnl" (link-target (.. dir "/link.png")))
        (assert.are.equal "new" (read-file (.. dir "/scene.fnl")))))

    (it "makes a folder for frames, and refuses a FIFO or a file there"
      (fn []
        (assert.is_true (output.ensure-dir! (.. dir "/rec/a/b")))
        (assert.are.equal :directory (. ((. (require :src.util.filestat) :stat) (.. dir "/rec/a/b")) :type))
        (assert.are.same [nil (.. dir "/fifo.png: is a FIFO, not a folder; refusing to write into it")]
                         [(output.ensure-dir! (.. dir "/fifo.png"))])
        (assert.are.same [nil (.. dir "/scene.fnl: is a file, not a folder; refusing to write into it")]
                         [(output.ensure-dir! (.. dir "/scene.fnl"))])))))

(describe "saving parameters"
  (fn []
    (before_each fresh!)

    (fn saved-scene [path value]
      ;; The override's base is the file's value (else the file's literal wins).
      (let [base (. (assert (load.load-file path)) :params 1 :value)
            scene (assert (load.load-file path nil {:overrides {:r {: value : base}}}))]
        (params.save! path scene.params)))

    (it "saves through a link into its target, and the link stays"
      (fn []
        (sh (.. "ln -s scene.fnl " dir "/via-link.fnl"))
        (assert.are.equal 1 (saved-scene (.. dir "/via-link.fnl") 0.75))
        (assert.are.equal "scene.fnl" (link-target (.. dir "/via-link.fnl")))
        (assert.truthy (: (read-file (.. dir "/scene.fnl")) :find "(param :r 0.75 " 1 true))))

    (it "does not write through a planted .saving link"
      (fn []
        (write-file (.. dir "/victim") "untouched\n")
        (sh (.. "ln -s victim " dir "/scene.fnl.saving"))
        (assert.are.equal 1 (saved-scene (.. dir "/scene.fnl") 0.75))
        (assert.are.equal "untouched\n" (read-file (.. dir "/victim")))
        (assert.are.equal "victim" (link-target (.. dir "/scene.fnl.saving")))))

    (it "writes a value at its range's edge so that it reads back the same and loads"
      (fn []
        (assert.are.equal 1 (saved-scene (.. dir "/scene.fnl") 1.23456789))
        (let [text (read-file (.. dir "/scene.fnl"))
              scene (assert (load.load-file (.. dir "/scene.fnl")))]
          (assert.truthy (text:find "(param :r 1.23456789 " 1 true) text)
          (assert.are.equal 1.23456789 (. scene.params 1 :value)))
        ;; Slider values; the compiler keeps 14 significant digits of a literal, so one
        ;; with more is written as the number it loads as, and that number is exact.
        (each [_ [v literal] (ipairs [[0.5 "0.5"] [(+ 0.7 0.1) "0.8"] [0.5925000000000001 "0.5925"]
                                      [(+ 0.5 (/ 1 3)) "0.83333333333333"] [1 "1"]])]
          (assert.are.equal 1 (saved-scene (.. dir "/scene.fnl") v))
          (let [text (read-file (.. dir "/scene.fnl"))
                loaded (. (assert (load.load-file (.. dir "/scene.fnl"))) :params 1 :value)]
            (assert.truthy (text:find (.. "(param :r " literal " ") 1 true) text)
            (assert.are.equal (tonumber literal) loaded)
            (assert.is_true (< (math.abs (- loaded v)) 1e-13))))
        ;; A value rounded past the edge is written as the edge.
        (assert.are.equal "(param :r 1.23456789 {:min 0.5 :max 1.23456789})"
                          (params.write-back "(param :r 1 {:min 0.5 :max 1.23456789})" "f.fnl"
                                             [{:name :r :kind :number :value 1.2345679
                                               :min 0.5 :max 1.23456789}]))))

    (it "refuses a scene that has become a FIFO"
      (fn []
        (let [scene (assert (load.load-file (.. dir "/scene.fnl") nil {:overrides {:r {:value 0.75 :base 1}}}))]
          (assert.are.same [nil (.. dir "/fifo.png: is a FIFO; refusing to write to it")]
                           [(params.save! (.. dir "/fifo.png") scene.params #scene-text)]))))))

(describe "the app's outputs"
  (fn []
    (setup fresh!)

    (each [_ [what args message]
           (ipairs [["--render to a link to the scene"
                     (.. "--render " dir "/scene.fnl --out " dir "/link.png --size 32x32")
                     (.. "error: --out " dir "/link.png: is the scene file " dir
                         "/scene.fnl (after following links); choose another name\n")]
                    ["--render to a FIFO"
                     (.. "--render " dir "/scene.fnl --out " dir "/fifo.png --size 32x32")
                     (.. "error: --out " dir "/fifo.png: is a FIFO; refusing to write to it\n")]
                    ["--render to a folder"
                     (.. "--render " dir "/scene.fnl --out " dir "/folder.png --size 32x32")
                     (.. "error: --out " dir "/folder.png: is a directory; refusing to write to it\n")]
                    ["--export-shader to a link to the scene"
                     (.. "--export-shader " dir "/scene.fnl --out " dir "/link.glsl")
                     (.. "error: --out " dir "/link.glsl: is the scene file " dir
                         "/scene.fnl (after following links); choose another name\n")]
                    ["--record into a FIFO"
                     (.. "--record " dir "/scene.fnl --out " dir "/fifo.png --frames 1 --size 32x32")
                     (.. "error: --out " dir "/fifo.png: is a FIFO, not a folder; refusing to write into it\n")]])]
      (it (.. "refuses " what ": exit 1, the path named, the scene intact")
        (fn []
          (let [before (doto (listing) table.sort)
                (code out) (run args)]
            (assert.are.equal 1 code out)
            (assert.are.equal message out)
            (assert.are.equal scene-text (read-file (.. dir "/scene.fnl")))
            (assert.are.same before (doto (listing) table.sort))))))

    (it "--record refuses a frame that is a link to the scene"
      (fn []
        (sh (.. "mkdir -p " dir "/rec && ln -sf ../scene.fnl " dir "/rec/frame-0001.png"))
        (let [(code out) (run (.. "--record " dir "/scene.fnl --out " dir "/rec --frames 1 --size 32x32"))]
          (assert.are.equal 1 code out)
          (assert.truthy (out:find (.. "error: " dir "/rec/frame-0001.png: is the scene file") 1 true) out)
          (assert.are.equal scene-text (read-file (.. dir "/scene.fnl"))))))))

;; Everything generated from every scene, written to one file to compare two checkouts
;; (a refactoring that must change nothing, byte for byte):
;;   luajit tools/fnl.lua tools/generated-dump.fnl OUT.txt [ref]
;; For each scene of scenes/, scenes/stress/, examples/, test/states/plain/ and
;; test/fixtures/: for two renderers (llvmpipe, a GPU's) and five plan variants
;; (default, folded, no grids, no field, folded without a field) every target's shader
;; (love, love-uniforms, core, probe, shadertoy) and the uniforms (textures by a hash
;; of their texels); for the default plan the Lua evaluators' source, and with `ref`
;; 108 pixels of the CPU reference (colour, steps, object, distance). Run it in each
;; checkout and diff the two files, leaving out the `###` header lines (their
;; variant's fields come in table order).

(local load (require :src.scene.load))
(local plan (require :src.render.plan))
(local codegen (require :src.render.codegen))
(local emit-lua (require :src.sdf.emit-lua))
(local camera (require :src.render.camera))
(local reference (require :src.reference))
(local uniforms (require :src.render.uniforms))

(local folders ["scenes" "scenes/stress" "examples" "test/states/plain" "test/fixtures"])
(local renderers ["llvmpipe" "NVIDIA"])
(local variants [{} {:fold? true} {:grids? false} {:field? false} {:fold? true :field? false}])
(local targets [:love :love-uniforms :core :probe :shadertoy])

(fn scene-files []
  (let [out []]
    (each [_ dir (ipairs folders)]
      (with-open [p (io.popen (.. "ls " dir "/*.fnl 2>/dev/null"))]
        (each [l (p:lines)] (table.insert out l))))
    out))

(fn number-text [v] (string.format "%.17g" v))

(fn texture-hash [t]
  ;; A hash of a texture's texels (its FFI data), or 0 without them.
  (var h 0)
  (when (= (type t.data) :cdata)
    (for [i 0 (- (* t.width t.height) 1)]
      (set h (% (+ (* h 31) (* 1000 (. t.data i))) 1000000007))))
  h)

(fn write-uniforms [f scene p]
  (f:write "## uniforms\n")
  (case (pcall uniforms.pack scene p (camera.from-scene scene) 64 48)
    (true us) (each [_ u (ipairs us)]
                (f:write u.name " " u.type " " (tostring u.count) " "
                         (table.concat (icollect [_ v (ipairs (or u.values []))] (number-text v)) ",")
                         (if u.texture
                             (.. " tex " u.texture.width "x" u.texture.height " "
                                 (number-text (texture-hash u.texture)))
                             "")
                         "\n"))
    (_ err) (f:write (tostring err) "\n")))

(fn write-reference [f scene p]
  (let [pixels (let [t []] (for [y 0 8] (for [x 0 11] (table.insert t [x y]))) t)]
    (f:write "## ref\n")
    (case (pcall reference.render-pixels scene p (camera.from-scene scene) 12 9 pixels)
      (true results) (each [_ c (ipairs results)]
                       (f:write (table.concat (icollect [_ v (ipairs c.color)] (number-text v)) " ")
                                " " (tostring c.steps) " " (tostring c.object) " "
                                (number-text (or c.distance 0)) "\n"))
      (_ err) (f:write (tostring err) "\n"))))

(fn write-plan [f scene p default? ref?]
  (var n 0)
  (each [_ target (ipairs targets)]
    (let [(_ text) (pcall codegen.shader p target)]
      (set n (+ n 1))
      (f:write "## " target "\n" (tostring text) "\n")))
  (write-uniforms f scene p)
  (when default?
    (let [(ok? c) (pcall emit-lua.compile p.tape)]
      (f:write "## lua\n" (if ok? c.source (tostring c)) "\n"))
    (when ref? (write-reference f scene p)))
  n)

(let [[out ref?] arg
      f (assert (io.open (assert out "usage: generated-dump.fnl OUT.txt [ref]") :w))]
  (var n 0)
  (each [_ file (ipairs (scene-files))]
    (case (load.load-file file)
      (nil err) (f:write "# " file " refused: " (tostring err) "\n")
      scene (each [_ renderer (ipairs renderers)]
              (each [_ flags (ipairs variants)]
                (f:write "### " file " " renderer " "
                         (table.concat (icollect [k v (pairs flags)] (.. k "=" (tostring v))) ",") "\n")
                (let [(ok? p) (pcall plan.scene->plan scene (plan.renderer-options renderer flags))]
                  (if (and ok? p)
                      (set n (+ n (write-plan f scene p (and (= renderer "llvmpipe") (= nil (next flags)))
                                              ref?)))
                      (f:write "plan failed " (tostring p) "\n")))))))
  (f:close)
  (print n "shaders"))

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
(local [out ref?] arg)
(local files [])
(each [_ dir (ipairs ["scenes" "scenes/stress" "examples" "test/states/plain" "test/fixtures"])]
  (let [p (io.popen (.. "ls " dir "/*.fnl 2>/dev/null"))]
    (each [l (p:lines)] (table.insert files l))
    (p:close)))
(local f (assert (io.open out :w)))
(var n 0)
(each [_ file (ipairs files)]
  (let [(scene err) (load.load-file file)]
    (if (not scene) (f:write "# " file " refused: " (tostring err) "\n")
        (each [_ renderer (ipairs ["llvmpipe" "NVIDIA"])]
          (each [_ flags (ipairs [{} {:fold? true} {:grids? false} {:field? false} {:fold? true :field? false}])]
            (let [(ok? p) (pcall plan.scene->plan scene (plan.renderer-options renderer flags))]
              (f:write "### " file " " renderer " " (table.concat (icollect [k v (pairs flags)] (.. k "=" (tostring v))) ",") "\n")
              (if (not (and ok? p)) (f:write "plan failed " (tostring p) "\n")
                  (do
                    (each [_ target (ipairs [:love :love-uniforms :core :probe :shadertoy])]
                      (let [(ok2? s) (pcall codegen.shader p target)]
                        (set n (+ n 1))
                        (f:write "## " target "\n" (tostring s) "\n")))
                    (let [(oku us) (pcall uniforms.pack scene p (camera.from-scene scene) 64 48)]
                      (f:write "## uniforms\n")
                      (if oku
                          (each [_ u (ipairs us)]
                            (f:write u.name " " u.type " " (tostring u.count) " "
                                     (table.concat (icollect [_ v (ipairs (or u.values []))] (string.format "%.17g" v)) ",")
                                     (if u.texture (.. " tex " u.texture.width "x" u.texture.height " " (let [d u.texture.data] (var h 0) (when (= (type d) :cdata) (for [i 0 (- (* u.texture.width u.texture.height) 1)] (set h (% (+ (* h 31) (* 1000 (. d i))) 1000000007)))) (string.format "%.17g" h))) "") "\n"))
                          (f:write (tostring us) "\n")))
                    (when (and (= renderer "llvmpipe") (= nil (next flags)))
                      (let [(ok3? c) (pcall emit-lua.compile p.tape)]
                        (f:write "## lua\n" (if ok3? c.source (tostring c)) "\n"))
                      (when ref?
                        (let [cam (camera.from-scene scene)
                              pixels (let [t []] (for [y 0 8] (for [x 0 11] (table.insert t [x y]))) t)
                              (ok4? cols) (pcall reference.render-pixels scene p cam 12 9 pixels)]
                          (f:write "## ref\n")
                          (if ok4?
                              (each [_ c (ipairs cols)] (f:write (table.concat (icollect [_ v (ipairs c.color)] (string.format "%.17g" v)) " ") " " (tostring c.steps) " " (tostring c.object) " " (string.format "%.17g" (or c.distance 0)) "\n"))
                              (f:write (tostring cols) "\n")))))))))))))
(f:close)
(print n "shaders")

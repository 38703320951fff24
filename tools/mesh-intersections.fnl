;; Counts a mesh's self-intersections (issue 46) under plain LuaJIT:
;;   luajit tools/fnl.lua tools/mesh-intersections.fnl SCENE [N] [FILE]
;; meshes SCENE at N cells on the CPU as `love . --mesh SCENE --resolution N` does
;; (or, with FILE, parses that mesh file back instead), then prints the pairs of
;; triangles that cross (src/mesh/intersect.fnl), the longest common segment in
;; cells and where it is, and the first few pairs. Exits 1 when any pair crosses.

(local export (require :src.mesh.export))
(local formats (require :src.mesh.formats))
(local intersect (require :src.mesh.intersect))
(local load (require :src.scene.load))

(fn fail [msg]
  (io.stderr:write (.. "mesh-intersections: " msg "\n"))
  (os.exit 2))

(let [[scene-path n file] arg
      _ (when (not scene-path) (fail "usage: mesh-intersections.fnl SCENE [N] [FILE]"))
      scene (or (load.load-file scene-path) (fail (.. "cannot load " scene-path)))
      resolution (or (tonumber n) 128)
      built (or (export.build scene {:resolution resolution :quiet? true}) (fail "nothing to mesh"))
      h built.grid.h
      m (if file
            (let [f (or (io.open file :rb) (fail (.. "cannot read " file)))
                  bytes (f:read "*a")]
              (f:close)
              (or (formats.decode bytes (formats.format-of file)) (fail "cannot parse")))
            built.mesh)
      t0 (os.clock)
      r (intersect.self-intersections m {:min-length (* 1e-6 h) :max-list 10})]
  (print (string.format "%s at %d: %d triangles; %d crossing pairs (%d coplanar), longest %.3f cells%s; %d pairs sharing a vertex meet beyond it; %d pairs tested in %.1f s"
                        scene-path resolution (/ (length m.triangles) 3) r.pairs r.coplanar
                        (/ r.longest h)
                        (if r.at (string.format " near (%.3f, %.3f, %.3f)" (unpack r.at)) "")
                        r.folds r.tested (- (os.clock) t0)))
  (each [_ [s t len] (ipairs r.list)]
    (print (string.format "  triangles %d and %d: %.3g cells" s t (/ len h))))
  (os.exit (if (= 0 r.pairs) 0 1)))

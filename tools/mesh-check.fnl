;; Checks a mesh file written by `love . --mesh` (issue 31) under plain LuaJIT:
;;   luajit tools/fnl.lua tools/mesh-check.fnl FILE.stl|.ply|.obj SCENE [N] [x0,y0,z0,x1,y1,z1]
;; parses it back, prints its topology (closed, 2-manifold, oriented), its volume
;; and area, and the largest distance of a vertex from the scene's surface by the CPU
;; evaluator, in cells of the grid --mesh SCENE --resolution N [--region ...] uses.
;; Exits 1 when the mesh is not a closed oriented 2-manifold.

(local formats (require :src.mesh.formats))
(local check (require :src.mesh.check))
(local mesh-scene (require :src.mesh.scene))
(local load (require :src.scene.load))

(fn fail [msg]
  (io.stderr:write (.. "mesh-check: " msg "\n"))
  (os.exit 2))

(let [[path scene-path n region-text] arg
      _ (when (not (and path scene-path)) (fail "usage: mesh-check.fnl FILE SCENE [N] [REGION]"))
      format (or (formats.format-of path) (fail (.. "not a mesh file: " path)))
      f (or (io.open path :rb) (fail (.. "cannot read " path)))
      bytes (f:read "*a")
      _ (f:close)
      (m err) (formats.decode bytes format)
      _ (when (not m) (fail err))
      scene (or (load.load-file scene-path) (fail (.. "cannot load " scene-path)))
      region (when region-text (or (mesh-scene.parse-region region-text) (fail "bad region")))
      selection (or (mesh-scene.select-objects scene region) (fail "nothing to mesh"))
      grid (mesh-scene.grid-for selection (or (tonumber n) mesh-scene.default-resolution))
      field (mesh-scene.cpu-field selection.scene)
      contour (require :src.mesh.contour)
      cut grid.cut
      distance (fn [x y z] (math.max (field.distance x y z) (contour.box-distance cut x y z)))
      t (check.topology m)
      worst (check.surface-distance m distance)]
  (print (check.describe t))
  (print (string.format "volume %.6g, area %.6g, largest vertex distance %.3f cells (cell %.4g)"
                        (check.volume m) (check.area m) (/ worst grid.h) grid.h))
  (os.exit (if t.manifold? 0 1)))

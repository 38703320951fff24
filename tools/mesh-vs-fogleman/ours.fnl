;; This project's side of tools/mesh-vs-fogleman/run.sh:
;;   luajit tools/fnl.lua tools/mesh-vs-fogleman/ours.fnl SCENE N
;; prints the mesh grid's region and cell (`region x0 y0 z0 x1 y1 z1 h`), then meshes
;; SCENE at N cells as `love . --mesh` does (export.build: the CPU evaluator, one
;; core) and prints `SECONDS TRIANGLES`, the seconds by the wall clock.

(local load (require :src.scene.load))
(local export (require :src.mesh.export))
(local mesh-scene (require :src.mesh.scene))
(local filestat (require :src.util.filestat))

(local [path n] [(. arg 1) (tonumber (. arg 2))])
(local scene (assert (load.load-file path)))
(local grid (mesh-scene.grid-for (assert (mesh-scene.select-objects scene)) n))
;; The cut (the region grown by a cell), which the mesh closes at: fogleman/sdf is
;; given the same box and cell.
(print (string.format "region %.6f %.6f %.6f %.6f %.6f %.6f %.8f"
                      (. grid.cut.lo 1) (. grid.cut.lo 2) (. grid.cut.lo 3)
                      (. grid.cut.hi 1) (. grid.cut.hi 2) (. grid.cut.hi 3) grid.h))
(local t0 (filestat.monotonic))
(local r (assert (export.build scene {:resolution n :quiet? true})))
(print (string.format "%.3f %d" (- (filestat.monotonic) t0) (/ (length r.mesh.triangles) 3)))

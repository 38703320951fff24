;; Adaptive meshes against uniform ones at the same largest distance from the
;; surface (issue 46):
;;   luajit tools/fnl.lua tools/mesh-adaptive.fnl SCENE N [SHARE ...]
;; meshes SCENE at N cells, measures the uniform mesh's largest distance from the
;; field's surface over its triangles (read a tenth of a cell apart), then meshes it with
;; --adaptive at that distance times each SHARE (default 1 and 0.5) and prints, for
;; each mesh: triangles, their share of the uniform mesh's, the largest distance in
;; cells, closed and 2-manifold, crossing pairs (and folds at a vertex), CPU seconds.

(local load (require :src.scene.load))
(local export (require :src.mesh.export))
(local contour (require :src.mesh.contour))
(local mesh-scene (require :src.mesh.scene))
(local check (require :src.mesh.check))
(local intersect (require :src.mesh.intersect))

(local [path n] [(. arg 1) (tonumber (or (. arg 2) 128))])
(local shares (let [given (fcollect [i 3 (length arg)] (tonumber (. arg i)))]
                (if (< 0 (length given)) given [1 0.5])))
(local scene (assert (load.load-file path)))

(fn measured [r seconds label uniform]
  (let [grid r.grid
        field (assert (mesh-scene.cpu-field (. (mesh-scene.select-objects scene) :scene)))
        values-of (contour.cut-field field grid.cut {:points 0 :work 0} (fn []) grid.h)
        worst (check.triangles-distance r.mesh (fn [flat] (values-of :check flat)) (* 0.1 grid.h))
        topo (check.topology r.mesh)
        x (intersect.self-intersections r.mesh {:min-length (* 1e-6 grid.h)})
        nt (/ (length r.mesh.triangles) 3)]
    (print (string.format "%-22s %8d triangles %6.1f%%  largest distance %.3f cells  %s  %d crossing pairs, %d folds  %.1f s"
                          label nt (* 100 (/ nt (or uniform nt))) (/ worst grid.h)
                          (if topo.manifold? "closed 2-manifold" (check.describe topo))
                          x.pairs x.folds seconds))
    (values worst nt)))

(print (string.format "%s at %d cells" path n))
(local t0 (os.clock))
(local uniform (assert (export.build scene {:resolution n :quiet? true})))
(local (worst count) (measured uniform (- (os.clock) t0) "uniform"))
(each [_ share (ipairs shares)]
  (let [t1 (os.clock)
        r (assert (export.build scene {:resolution n :quiet? true :adaptive (* share worst)}))]
    (measured r (- (os.clock) t1) (string.format "adaptive %.2f x" share) count)))

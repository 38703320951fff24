;; The mesh volume figures of docs/mesh.md (issue 31), under plain LuaJIT:
;;   luajit tools/fnl.lua tools/mesh-volumes.fnl [N...]   (default 32 128)
;; a sphere, a rotated box and a torus meshed on the CPU at N cells: the volume's
;; error against the exact one, and the time.

(local load (require :src.scene.load))
(local export (require :src.mesh.export))
(local check (require :src.mesh.check))

(local shapes
  [["sphere" "{:kind :sphere :radius 1 :pos [0.1 0.2 0.3]}" (* (/ 4 3) math.pi)]
   ["rotated box" "{:kind :box :size [2 1 0.5] :rotate [30 45 60] :pos [0.1 0.2 0.3]}" 1]
   ["torus" "{:kind :torus :radius 1 :thickness 0.3 :rotate [20 0 0]}" (* 2 math.pi math.pi 0.09)]])

(let [ns (if (> (length arg) 0) (icollect [_ a (ipairs arg)] (tonumber a)) [32 128])]
  (each [_ n (ipairs ns)]
    (each [_ [name obj v] (ipairs shapes)]
      (let [s (assert (load.load-string (.. "{:objects [" obj "]}") name))
            t0 (os.clock)
            r (assert (export.build s {:resolution n :quiet? true}))
            got (check.volume r.mesh)]
        (print (string.format "N %d  %-11s  volume %.6f, exact %.6f, error %+.4f%%, %d triangles, %.2f s CPU"
                              n name got v (* 100 (/ (- got v) v)) (/ (length r.mesh.triangles) 3)
                              (- (os.clock) t0)))))))

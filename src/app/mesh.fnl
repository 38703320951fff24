;; `love . --mesh SCENE --out FILE.stl|FILE.ply|FILE.obj [--resolution N] [--region
;; x0,y0,z0,x1,y1,z1] [--gpu] [--adaptive E]`: the scene's objects as a closed mesh file, sampled by
;; the CPU evaluator or, with --gpu, by the generated GLSL. Progress on stderr; one line
;; on stdout saying what was written and what was left out or cut.

(local frame (require :src.backend.frame))
(local output (require :src.util.output))
(local export (require :src.mesh.export))
(local stop (require :src.app.stop))

(fn summary [path result]
  "The line printed after a mesh is written."
  (let [m result.mesh
        a result.stats.adaptive]
    (string.format "wrote %s: %d triangles, %d vertices, cells of %.4g (%dx%dx%d grid)%s, %.1f s; %s"
                   path (/ (length m.triangles) 3) (/ (length m.positions) 3) result.grid.h
                   (. result.grid.dims 1) (. result.grid.dims 2) (. result.grid.dims 3)
                   (if a (string.format ", adaptive within %.4g: %d of the grid's %d triangles"
                                        a.error a.after a.before)
                       "")
                   result.seconds result.message)))

(fn run [o]
  "Mesh o.scene into o.out. Returns true, or nil and a message."
  (let [out-options {:protect [o.scene] :label (.. "--out " o.out)}]
    (case (output.check o.out out-options)
      (nil err) (values nil err)
      _ (case (frame.load-scene o.scene)
          (nil err) (values nil err)
          scene
          (case (export.build scene {:resolution o.resolution :region o.region
                                     :adaptive o.adaptive
                                     :clock love.timer.getTime :stop? stop.asked?
                                     :stop-message (.. stop.message "; nothing written")
                                     :field (when o.gpu? (. (require :src.mesh.gpu) :gpu-field))})
            (nil err) (values nil (.. o.scene ": " err))
            result (case (export.write! result.mesh o.out {:name o.scene
                                                           :protect out-options.protect
                                                           :label out-options.label})
                     (nil err) (values nil err)
                     _ (do (print (summary o.out result)) true)))))))

(fn export-shown [scene scene-path ?resolution]
  "F9 in the player: mesh `scene` as it is shown (its parameters' values, its
functions of time at the shown time) with the GPU field, `?resolution` cells (128),
into a PLY beside the scene file, named after it and the time. Returns true and the
line to show, or nil and a message."
  (let [dir (or (scene-path:match "^(.*)/[^/]*$") ".")
        base (or (scene-path:match "([^/]+)%.fnl$") "scene")
        path (.. dir "/" base "-mesh-" (os.date "%Y%m%d-%H%M%S") ".ply")]
    (case (export.build scene {:resolution ?resolution :clock love.timer.getTime :quiet? true
                               :field (. (require :src.mesh.gpu) :gpu-field)})
      (nil err) (values nil err)
      result (case (export.write! result.mesh path {:name scene-path :protect [scene-path]
                                                    :label path})
               (nil err) (values nil err)
               _ (values true (summary path result))))))

{: run : summary : export-shown}

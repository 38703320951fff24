;; One rendered frame in LÖVE: scene file in, canvas out. Shared by the player, the
;; command-line modes and the benchmark.

(local scene-mod (require :src.scene.load))
(local worker (require :src.scene.worker))
(local plan-mod (require :src.render.plan))
(local uniforms (require :src.render.uniforms))
(local gpu (require :src.backend.gpu))
(local output (require :src.util.output))

(fn read-text [path]
  "The text of the scene file at `path`: relative to the working directory first, then
the bundled scenes inside the game folder (see files.read-user)."
  (scene-mod.read-capped path))

(fn load-scene [path ?options]
  "Load and validate the scene file at `path` in the scene worker (`?options` as
scene-mod.load-string takes them): scene, or nil and a message."
  (worker.load-file path read-text ?options))

(fn render-to-canvas! [cache canvas scene plan cam ?rows ?extra]
  "Draw `scene` (lowered to `plan`, seen by `cam`) into `canvas`; only the rows
[y0 y1) of `?rows` when given (the rest of the canvas is kept); `?extra` uniforms
after the scene's (uniforms.prior's). Returns true, or nil and a message when the
shader does not compile."
  (let [(shader err) (gpu.shader-for cache plan)]
    (if (not shader)
        (values nil err)
        (let [(w h) (canvas:getDimensions)]
          (love.graphics.push :all)
          (love.graphics.setCanvas canvas)
          (case ?rows
            [y0 y1] (love.graphics.setScissor 0 y0 w (math.max 1 (- y1 y0)))
            _ (love.graphics.clear 0 0 0 1))
          (gpu.draw! shader (doto (uniforms.pack scene plan cam w h)
                              (#(each [_ u (ipairs (or ?extra []))] (table.insert $ u))))
                     w h)
          (love.graphics.pop)
          true))))

(fn write-png [canvas path ?options]
  "Write `canvas` as a PNG file at `path` (any path, not only LÖVE's save folder)
through output.write! (`?options` as it takes them: :protect, :label). Returns true,
or nil and a message naming the path."
  (let [data (canvas:newImageData)
        file-data (data:encode :png)
        bytes (file-data:getString)]
    (data:release)
    (file-data:release)
    (output.write! path bytes ?options)))

(fn renderer-options [?options]
  "`?options` for plan.scene->plan, with what suits this renderer filled in (see
plan.renderer-options). Modes with no graphics (the CPU probe, --tree) draw nothing:
their options are left as given."
  (case (when love.graphics (pcall love.graphics.getRendererInfo))
    (true _ _ _ device) (plan-mod.renderer-options device ?options)
    _ (or ?options {})))

(fn plan-for [scene ?options]
  "The plan of `scene` for this renderer (see plan.scene->plan and
plan.renderer-options)."
  (plan-mod.scene->plan scene (renderer-options ?options)))

{: load-scene : read-text : render-to-canvas! : write-png : plan-for}

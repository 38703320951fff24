;; One rendered frame in LÖVE: scene file in, canvas out. Shared by the player, the
;; command-line modes and the benchmark.

(local scene-mod (require :src.scene))
(local plan-mod (require :src.plan))
(local uniforms (require :src.uniforms))
(local gpu (require :src.gpu))

(fn read-text [path]
  ;; A path on the command line is relative to the working directory; the bundled
  ;; scenes are also found inside the game folder when LÖVE runs from elsewhere.
  (case (io.open path :rb)
    f (let [s (f:read :*a)] (f:close) s)
    (nil err) (if (love.filesystem.getInfo path :file)
                  (love.filesystem.read path)
                  (values nil err))))

(fn load-scene [path]
  "Load and validate the scene file at `path`: scene, or nil and a message."
  (scene-mod.load-file path read-text))

(fn render-to-canvas! [cache canvas scene plan cam]
  "Draw `scene` (lowered to `plan`, seen by `cam`) into `canvas`. Returns true, or nil
and a message when the shader does not compile."
  (let [(shader err) (gpu.shader-for cache plan)]
    (if (not shader)
        (values nil err)
        (let [(w h) (canvas:getDimensions)]
          (love.graphics.push :all)
          (love.graphics.setCanvas canvas)
          (love.graphics.clear 0 0 0 1)
          (gpu.draw! shader (uniforms.pack scene plan cam w h) w h)
          (love.graphics.pop)
          true))))

(fn write-png [canvas path]
  "Write `canvas` as a PNG file at `path` (any path, not only LÖVE's save folder)."
  (let [data (canvas:newImageData)
        file-data (data:encode :png)
        (out err) (io.open path :wb)]
    (data:release)
    (if out
        (do (out:write (file-data:getString))
            (out:close)
            true)
        (values nil (.. path ": cannot write: " (tostring err))))))

(fn plan-for [scene ?options]
  "The plan of `scene` (see plan.scene->plan)."
  (plan-mod.scene->plan scene ?options))

{: load-scene : read-text : render-to-canvas! : write-png : plan-for}

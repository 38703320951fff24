;; `love GAME --warm-shader FILE.glsl`: the player's compile helper (see warm.fnl).
;; Compiles the shader in FILE and draws it once into a small canvas, so the driver's
;; on-disk cache holds the program and the code of its first draw; exits 0, or 1 with
;; the driver's message. conf.lua loads this module instead of main.fnl, so the helper
;; starts in about a quarter of a second (the player's modules take a second to
;; compile).

(local quad (require :src.backend.quad))

(fn shader-path [args]
  (var path nil)
  (each [i a (ipairs args)]
    (when (= a "--warm-shader") (set path (. args (+ i 1)))))
  path)

(fn textures [source]
  "The textures the player will bind, from the lines `//warm-texture NAME W H` it puts
before the shader: [[name w h] ...]."
  (icollect [name w h (source:gmatch "//warm%-texture ([%w_]+) (%d+) (%d+)\n")]
    [name (tonumber w) (tonumber h)]))

(fn shader-text [source]
  ;; Without those lines: the text the player compiles, so that the driver's cache
  ;; finds it.
  (pick-values 1 (source:gsub "//warm%-texture [^\n]*\n" "")))

(fn fail! [message]
  (io.stderr:write (.. "error: " message "\n"))
  (love.event.quit 1))

(fn warm! [args]
  "Compile and draw the shader named after --warm-shader in `args`."
  (let [path (shader-path args)
        source (case (and path (io.open path :rb))
                 f (let [t (f:read :*a)] (f:close) t))]
    (if (not source) (fail! (.. (tostring path) ": cannot read the shader"))
        (case (pcall love.graphics.newShader (shader-text source))
          (false err) (fail! (.. path ": the shader did not compile:\n" (tostring err)))
          (true shader) (let [canvas (love.graphics.newCanvas 8 8)]
                          ;; A field's textures as the player makes them: rgba32f,
                          ;; sampled nearest, of the same size (gpu.float-image). The
                          ;; driver's code for the shader depends on the format, the
                          ;; sampler and whether each side is a power of two.
                          (each [_ [name w h] (ipairs (textures source))]
                            (when (shader:hasUniform name)
                              (let [image (love.graphics.newImage
                                            (love.image.newImageData w h :rgba32f))]
                                (image:setFilter :nearest :nearest)
                                (shader:send name image))))
                          (quad.draw-into! canvas shader)
                          ;; Reading a pixel back waits until the draw has run.
                          (: (canvas:newImageData 1 1 0 0 1 1) :release)
                          (love.event.quit 0))))))

(fn install! []
  "Make LÖVE run the helper: conf.lua calls this instead of loading main.fnl."
  (set love.errorhandler
       (fn [message]
         (io.stderr:write (.. "error: " (tostring message) "\n"))
         (os.exit 1)))
  (set love.load warm!))

{: install! : warm! : shader-path : textures : shader-text}

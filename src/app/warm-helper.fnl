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

(fn fail! [message]
  (io.stderr:write (.. "error: " message "\n"))
  (love.event.quit 1))

(fn warm! [args]
  "Compile and draw the shader named after --warm-shader in `args`."
  (let [path (shader-path args)
        source (case (and path (io.open path :rb))
                 f (let [t (f:read :*a)] (f:close) t))]
    (if (not source) (fail! (.. (tostring path) ": cannot read the shader"))
        (case (pcall love.graphics.newShader source)
          (false err) (fail! (.. path ": the shader did not compile:\n" (tostring err)))
          (true shader) (let [canvas (love.graphics.newCanvas 8 8)]
                          (quad.draw-into! canvas shader)
                          ;; Reading a pixel back waits until the draw has run.
                          (: (canvas:newImageData 1 1 0 0 1 1) :release)
                          (love.event.quit 0))))))

(set love.errorhandler
     (fn [message]
       (io.stderr:write (.. "error: " (tostring message) "\n"))
       (os.exit 1)))
(set love.load warm!)

{: warm! : shader-path}

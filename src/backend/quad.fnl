;; The full-screen quad every frame is drawn with, apart from the rest of gpu.fnl so
;; that the player's compile helper (src/app/warm-helper.fnl) draws exactly as the
;; player does while loading next to nothing.

(fn draw! [shader width height]
  "Draw a `width` x `height` rectangle with `shader` into the current target."
  (love.graphics.push :all)
  (love.graphics.setShader shader)
  (love.graphics.setColor 1 1 1 1)
  (love.graphics.rectangle :fill 0 0 width height)
  (love.graphics.pop))

(fn draw-into! [canvas shader]
  "Clear `canvas` and draw the quad into it with `shader`, as frame.render-to-canvas!
does (the driver compiles a variant of the shader for the target's format and the
blend state on the first draw)."
  (let [(w h) (canvas:getDimensions)]
    (love.graphics.push :all)
    (love.graphics.setCanvas canvas)
    (love.graphics.clear 0 0 0 1)
    (draw! shader w h)
    (love.graphics.pop)))

{: draw! : draw-into!}

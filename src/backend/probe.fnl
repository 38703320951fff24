;; `--probe --gpu`: the scene's generated GLSL evaluated at given points, one pixel per
;; point, read back from a float canvas. The points travel in a float texture.

(local codegen (require :src.render.codegen))
(local uniforms (require :src.render.uniforms))
(local gpu (require :src.backend.gpu))

(local row-length 1024)

(fn points-image [points w h]
  (let [data (love.image.newImageData w h :rgba32f)]
    (each [i [x y z] (ipairs points)]
      (let [k (- i 1)]
        (data:setPixel (% k w) (math.floor (/ k w)) x y z 1)))
    (let [image (love.graphics.newImage data)]
      (image:setFilter :nearest :nearest)
      (data:release)
      image)))

(fn gpu-evaluator [scene plan]
  "A function from a list of points to {:distance :color [r g b] :mirror} for each
from the generated GLSL (`plan` made with :probe? true), or nil and a message (the
function too returns nil and a message when a batch fails). The shader is compiled
once for every batch."
  (let [(source serr) (codegen.shader plan :probe)
        (shader err) (if source (gpu.compile-source source "probe") (values nil serr))]
    (if (not shader) (values nil err)
        (fn [points]
          (let [n (length points)
                w (math.max 1 (math.min n row-length))
                h (math.max 1 (math.ceil (/ n row-length)))
                image (points-image points w h)
                canvas (love.graphics.newCanvas w h {:format :rgba32f})
                cam {:pos [0 0 0] :yaw 0 :pitch 0 :fov 60}
                us (uniforms.pack scene plan cam w h)
                read (fn [channel]
                       (love.graphics.push :all)
                       (love.graphics.setCanvas canvas)
                       (love.graphics.clear 0 0 0 0)
                       ;; Values, not colours: no blending with what is there.
                       (love.graphics.setBlendMode :replace :premultiplied)
                       (shader:send :uPoints image)
                       (shader:send :uProbeChannel channel)
                       (gpu.draw! shader us w h)
                       (love.graphics.pop)
                       (canvas:newImageData))
                a (read 0)
                b (read 1)
                out (fcollect [i 1 n]
                      (let [k (- i 1) x (% k w) y (math.floor (/ k w))
                            (d r g bl) (a:getPixel x y)
                            m (b:getPixel x y)]
                        {:distance d :color [r g bl] :mirror m}))]
            (a:release) (b:release) (image:release) (canvas:release)
            out)))))

{: gpu-evaluator}

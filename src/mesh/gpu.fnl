;; `--mesh --gpu`: the scene's generated GLSL as a field for src/mesh/contour.fnl (the
;; mesher's time 1.5 to 4 times shorter than with the CPU evaluator's: docs/mesh.md). A
;; batch of points goes up as a float texture, one texel a point, and comes back from a
;; float canvas (the :probe codegen target, as `--probe --gpu`: channel 0 gives the
;; distance and the material's colour). The texture and canvas are filled and read
;; through LÖVE's FFI pointers, so a batch costs no Lua table per point. Needs LÖVE (a
;; graphics context).

(local ffi (require :ffi))
(local codegen (require :src.render.codegen))
(local uniforms (require :src.render.uniforms))
(local gpu (require :src.backend.gpu))
(local frame (require :src.backend.frame))
(local mesh-scene (require :src.mesh.scene))

(local row-length 1024)

(fn gpu-field [scene]
  "The generated GLSL of `scene` as a field for contour.mesh (:distances and
:colors, float32), or nil and a message when its shader does not compile."
  ;; As --probe --gpu plans it: with what suits this renderer (frame.plan-for).
  (case (frame.plan-for scene {:view :glow :probe? true})
    (nil err) (values nil err)
    plan
    (let [(source serr) (codegen.shader plan :probe)
          (shader err) (if source (gpu.compile-source source "mesh") (values nil serr))
          cam {:pos [0 0 0] :yaw 0 :pitch 0 :fov 60}]
      (if (not shader) (values nil err)
          (let [run (fn [flat n ?skip]
                      ;; Distances and colours of the n points of `flat` after its
                      ;; first ?skip: one float pointer to w * h texels of d r g b.
                      (let [w (math.max 1 (math.min n row-length))
                            h (math.max 1 (math.ceil (/ n row-length)))
                            data (love.image.newImageData w h :rgba32f)
                            p (ffi.cast "float*" (data:getFFIPointer))]
                        (for [k 0 (- n 1)]
                          (let [b (* 3 (+ k (or ?skip 0))) q (* 4 k)]
                            (tset p q (. flat (+ b 1))) (tset p (+ q 1) (. flat (+ b 2)))
                            (tset p (+ q 2) (. flat (+ b 3))) (tset p (+ q 3) 1)))
                        (let [image (love.graphics.newImage data)
                              canvas (love.graphics.newCanvas w h {:format :rgba32f})]
                          (image:setFilter :nearest :nearest)
                          (love.graphics.push :all)
                          (love.graphics.setCanvas canvas)
                          (love.graphics.clear 0 0 0 0)
                          (love.graphics.setBlendMode :replace :premultiplied)
                          (shader:send :uPoints image)
                          (shader:send :uProbeChannel 0)
                          (gpu.draw! shader (uniforms.pack scene plan cam w h) w h)
                          (love.graphics.pop)
                          (let [out (canvas:newImageData)]
                            (data:release) (image:release) (canvas:release)
                            out))))]
            {:distances (fn [flat n ?skip]
                          (let [out (run flat n ?skip)
                                p (ffi.cast "float*" (out:getFFIPointer))
                                ds (fcollect [k 0 (- n 1)] (tonumber (. p (* 4 k))))]
                            (out:release)
                            ds))
             :colors (fn [flat n]
                       (let [out (run flat n)
                             p (ffi.cast "float*" (out:getFFIPointer))
                             cs []]
                         (for [k 0 (- n 1)]
                           (for [c 1 3]
                             (tset cs (+ (* 3 k) c) (tonumber (. p (+ (* 4 k) c))))))
                         (out:release)
                         cs))
             ;; float32 distances: a step of 1/20 cell keeps their rounding (about
             ;; 1e-7 of the coordinates) a small part of the difference.
             :step 0.05
             ;; The level set as the CPU's field meshes it (see its :offset).
             :offset mesh-scene.surface-offset})))))

{: gpu-field}

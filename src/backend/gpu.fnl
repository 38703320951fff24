;; LÖVE side of rendering: compiles generated shaders (cached by plan structure), sends
;; uniforms and draws the full-screen quad. The only core module that touches love.*.

(local codegen (require :src.render.codegen))
(local uniforms (require :src.render.uniforms))
(local field (require :src.render.field))
(local quad (require :src.backend.quad))

(local max-cached-shaders 8)

(fn new-cache []
  "An empty shader cache: plan key -> compiled LÖVE shader, least recently used first.
:compiles and :released count shaders made and released (live = compiles - released),
:compile-seconds adds up the time the compiles took."
  {:shaders {} :order [] :compiles 0 :released 0 :compile-seconds 0})

(fn touch! [cache key]
  (for [i (length cache.order) 1 -1]
    (when (= (. cache.order i) key) (table.remove cache.order i)))
  (table.insert cache.order key))

(fn evict! [cache]
  (while (> (length cache.order) max-cached-shaders)
    (let [key (table.remove cache.order 1)
          shader (. cache.shaders key)]
      (tset cache.shaders key nil)
      (when shader
        (shader:release)
        (set cache.released (+ cache.released 1))))))

(fn compile-source [source ?label]
  "Compile GLSL `source` into a LÖVE shader, or nil and the driver's message."
  (let [(ok? shader) (pcall love.graphics.newShader source)]
    (if ok? shader
        (values nil (.. (or ?label "shader") ": the generated shader did not compile:\n"
                        (tostring shader))))))

(fn compile-plan [plan ?label]
  "Compile `plan`'s LÖVE shader, or nil and a message. A driver that refuses its flat
varyings (codegen's pack-varyings) gets the shader that reads uniforms instead."
  (let [label (or ?label plan.key)
        (source serr) (codegen.shader plan :love)
        (shader err) (if source (compile-source source label) (values nil serr))]
    (if shader shader
        (not source) (values nil err)
        (let [(plain perr) (codegen.shader plan :love-uniforms)
              fallback (when plain (compile-source plain label))]
          (if fallback fallback (values nil (or perr err)))))))

(fn cached? [cache plan]
  "True when `plan`'s shader is compiled and in `cache`."
  (not= nil (. cache.shaders plan.key)))

(fn shader-for [cache plan]
  "The compiled shader for `plan`, compiling it on a cache miss. Returns the shader and
whether it was compiled now, or nil and a message."
  (let [cached (. cache.shaders plan.key)]
    (if cached
        (do (touch! cache plan.key) (values cached false))
        (let [t0 (love.timer.getTime)
              (shader err) (compile-plan plan)]
          (set cache.compile-seconds (+ cache.compile-seconds (- (love.timer.getTime) t0)))
          (if shader
              (do (tset cache.shaders plan.key shader)
                  (set cache.compiles (+ cache.compiles 1))
                  (touch! cache plan.key)
                  (evict! cache)
                  (values shader true))
              (values nil err))))))

(fn love-values [u]
  ;; LÖVE's Shader:send takes numbers for float and int, booleans for bool and one
  ;; table per element for vectors.
  (let [n (. uniforms.components u.type)
        vs u.values]
    (if (= u.type :bool) (icollect [_ v (ipairs vs)] (not= v 0))
        (= n 1) vs
        (fcollect [i 1 (length vs) n]
          (fcollect [j 0 (- n 1)] (. vs (+ i j)))))))

;; A field's textures as LÖVE images, by the texture table they were made from: the
;; tables live as long as their plan, so a texture is uploaded once, not every frame.
;; A value edit makes a new plan whose textures differ from the last ones only where
;; the edit reached: the last image of that uniform is kept, and only the texels that
;; changed are uploaded into it (field.changed-spans).
(local images (setmetatable {} {:__mode :k}))
(local last-images {})

(fn fill-floats! [data tex offset count]
  ;; `count` floats of texture `tex` from `offset` (0-based; missing ones 0) into
  ;; `data`: copied from its float32 :floats, or converted from its Lua list :data.
  (let [ffi (require :ffi)
        ptr (ffi.cast "float *" (data:getFFIPointer))]
    (if (or tex.floats tex.field)
        (ffi.copy ptr (+ (field.floats-of tex) offset) (* 4 count))
        (let [vs tex.data]
          (for [i 0 (- count 1)] (tset ptr i (or (. vs (+ offset i 1)) 0)))))))

(fn new-float-image [tex]
  (let [data (love.image.newImageData tex.width tex.height :rgba32f)]
    (fill-floats! data tex 0 (* 4 tex.width tex.height))
    (let [image (love.graphics.newImage data)]
      (image:setFilter :nearest :nearest)
      (data:release)
      image)))

(fn float-image [name tex]
  "The rgba32f image of texture `tex` ({:width :height :data}) for uniform `name`:
cached; else the last image of `name` with the changed texels replaced when the
sizes match; else a new one."
  (or (. images tex)
      (let [last (. last-images name)
            spans (when (and last (= last.texture.height tex.height))
                    (field.changed-spans last.texture tex))
            image (if spans
                      (do (each [_ [row first final] (ipairs spans)]
                            (let [n (+ 1 (- final first))
                                  data (love.image.newImageData n 1 :rgba32f)]
                              (fill-floats! data tex (* 4 (+ first (* row tex.width))) (* 4 n))
                              (last.image:replacePixels data nil nil first row)
                              (data:release)))
                          ;; The old table no longer describes the image.
                          (tset images last.texture nil)
                          last.image)
                      (new-float-image tex))]
        (tset images tex image)
        (tset last-images name {:texture tex : image})
        ;; LÖVE keeps a copy and the driver another: a large static field's
        ;; floats may go (the next value edit uploads the whole texture).
        (field.release-floats! tex)
        image)))

(fn send! [shader us]
  "Send the uniform list `us` (from uniforms.pack) to `shader`, skipping any the driver
dropped."
  (each [_ u (ipairs us)]
    (when (shader:hasUniform u.name)
      (if (= u.type :texture)
          (shader:send u.name (float-image u.name u.texture))
          (= u.type :image)
          (shader:send u.name u.image)
          (shader:send u.name ((or table.unpack unpack) (love-values u)))))))

(fn draw! [shader us width height]
  "Draw the full-screen quad of `width` x `height` with `shader` into the current target."
  (send! shader us)
  (quad.draw! shader width height))

(fn finish! [canvas]
  "Wait until the GPU has finished drawing into `canvas` (reads back one pixel)."
  (: (canvas:newImageData 1 1 0 0 1 1) :release))

{: new-cache : cached? : shader-for : compile-source : compile-plan : send! : draw! : finish!}

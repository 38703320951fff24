;; Shader export: a scene's generated shader with every uniform baked in as a constant,
;; in Shadertoy's form (mainImage, iResolution), to paste into Shadertoy or any GLSL
;; host. Pure: runs under plain LuaJIT.

(local codegen (require :src.render.codegen))
(local field (require :src.render.field))
(local uniforms (require :src.render.uniforms))
(local camera (require :src.render.camera))

(fn shadertoy [scene plan]
  "The shader of `scene` lowered to `plan`, seen from the scene's camera, as a
Shadertoy fragment shader: every uniform a constant but the resolution (iResolution).
Returns the text, or nil and a message."
  (case (if plan.field
            (let [things (if (= 0 (length plan.field.kinds.marched)) " spheres and boxes" " objects")]
              (values nil (.. "export: " scene.name " keeps its " plan.field.count
                              things " in float textures (a field), which a Shadertoy"
                              " shader cannot hold; export takes scenes of fewer than "
                              field.min-objects things)))
            ;; Every uniform declared as a constant of its value, but the resolution.
            (let [values-by-name (collect [_ u (ipairs (uniforms.pack scene plan (camera.from-scene scene) 1 1))]
                                   ;; The tape's rows as the array they are in a texture.
                                   u.name (if (and (= u.type :texture) u.count)
                                              {:name u.name :type :vec4 :count u.count
                                               :values u.texture.data}
                                              u))]
              (var missing nil)
              (let [text (codegen.shader plan :shadertoy
                                         (fn [d]
                                           (if (= d.name "uResolution") (.. "vec2 uResolution;" d.trailer)
                                               (case (. values-by-name d.name)
                                                 u (.. (uniforms.constant u) d.trailer)
                                                 _ (do (set missing d.name) d.text)))))]
                (if missing (values nil (.. "export: no value for the uniform " missing))
                    text))))
    (nil err) (values nil err)
    text (let [out [(.. "// " scene.name ": exported by `love . --export-shader` (Shadertoy form; every")
                    "// value is baked in, so a changed scene needs another export)."]]
           (when scene.animated
             ;; Functions of time are Lua code run in the sandbox; GLSL cannot run them.
             (table.insert out "// The scene's functions of time are baked at t = 0 (iTime is not used)."))
           (.. (table.concat out "\n") "\n" text))))

{: shadertoy}

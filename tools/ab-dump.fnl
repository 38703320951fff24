;; The shader and uniforms of a scene as this checkout makes them, for tools/ab-run:
;; run it from any checkout (old or new code) as
;;   luajit tools/fnl.lua PATH/ab-dump.fnl SCENE W H OUT.lua [FLAGS]
;; FLAGS, comma-separated: fold (values folded into the code), nogrids (no grids over
;; instance groups: every member evaluated everywhere), nofield (spheres and boxes in
;; the tape, not a field), still (the player's anti-aliased still: 4 x 4 adaptive,
;; drawn without the centre rays' picture). A dump is also what tools/compile-run
;; times: `love tools/compile-run ROUNDS W H A.lua B.lua`.
;; then `SDL_VIDEODRIVER=offscreen love tools/ab-run W H FRAMES A.lua B.lua` times them
;; in turn. LÖVE's shader (flat varyings), uniforms read once as on llvmpipe.
(local load (require :src.scene.load))
(local plan (require :src.render.plan))
(local codegen (require :src.render.codegen))
(local uniforms (require :src.render.uniforms))
(local camera (require :src.render.camera))
(local [file w h out fold] arg)
(local w (tonumber w))
(local h (tonumber h))
(let [scene (assert (load.load-file file))
      flag? #(not= nil (string.find (or fold "") $1))
      still? (flag? "still")
      p (assert (plan.scene->plan scene (plan.renderer-options "llvmpipe" {:fold? (flag? "fold")
                                                                      :grids? (not (flag? "nogrids"))
                                                                      :field? (not (flag? "nofield"))
                                                                      :samples (when still? 4)
                                                                      :adaptive? (when still? true)})))
      source (assert (codegen.shader p :love))
      us (uniforms.pack scene p (camera.from-scene scene) w h)
      f (assert (io.open out :w))]
  (f:write "return {source=[==[" source "]==], uniforms={\n")
  (each [_ u (ipairs us)]
    (f:write "{name=\"" u.name "\", type=\"" u.type "\"")
    (when u.values
      (f:write ", values={" (table.concat (icollect [_ v (ipairs u.values)] (string.format "%.17g" v)) ",") "}"))
    (when u.texture
      (f:write ", texture={width=" u.texture.width ", height=" u.texture.height ", data={"
               (table.concat (icollect [_ v (ipairs u.texture.data)] (string.format "%.9g" v)) ",") "}}"))
    (f:write "},\n"))
  (f:write "}}\n")
  (f:close))

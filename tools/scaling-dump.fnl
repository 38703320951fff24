;; The benchmark's scaling scene (test/bench/report.fnl's scaling-scene: n spheres in a
;; 40 x 40 x 10 region over a floor, radius 1.2 sqrt(10 / n), hard shadows, one mirror
;; bounce) as tools/ab-dump.fnl writes a scene, for tools/ab-run. The spheres are made
;; here in Lua with the scene file's generator, not by the scene sandbox, so that any
;; count loads (the sandbox's step budget refuses large loops). Run it from any checkout
;; (old or new code) as
;;   luajit PATH/tools/fnl.lua PATH/tools/scaling-dump.fnl N W H OUT.lua [CELLS-PER-OBJECT|-
;;     [SHADOWS REFLECTIONS]]
;; (CELLS-PER-OBJECT - for the checkout's default; SHADOWS true or false and
;; REFLECTIONS a count override the scene's: what the frame time consists of)
;; (tools/scaling-ab.sh runs it for several counts, in this checkout and another, and
;; times them interleaved).
(local load (require :src.scene.load))
(local plan (require :src.render.plan))
(local codegen (require :src.render.codegen))
(local uniforms (require :src.render.uniforms))
(local camera (require :src.render.camera))
(local [n w h out cells shadows reflections] arg)
(local n (tonumber n))
(local w (tonumber w))
(local h (tonumber h))

(fn spheres [n]
  ;; The scene file's spheres: the same generator and order.
  (var seed 12345)
  (fn rnd []
    (set seed (% (+ (* seed 1103515245) 12345) 2147483648))
    (/ seed 2147483648))
  (let [r (* 1.2 (math.sqrt (/ 10 n)))]
    (fcollect [i 1 n]
      (let [x (+ -20 (* 40 (rnd))) y (+ -20 (* 40 (rnd))) z (+ 0.5 (* 10 (rnd)))]
        {:kind :sphere :pos [x y z] :radius r :index (+ i 1)
         :color [(+ 0.3 (* 0.7 (rnd))) (+ 0.3 (* 0.7 (rnd))) (+ 0.3 (* 0.7 (rnd)))]}))))

(let [scene (assert (load.load-string
                     (.. "{:name \"scaling " n "\" :camera {:pos [0 -35 12] :yaw 90 :pitch 15 :fov 60}"
                         " :light {:pos [-20 -30 40]} :render {:shadows " (or shadows "true")
                         " :reflections " (or reflections "1") "}"
                         " :objects [{:kind :plane :height 0 :color [0.6 0.6 0.6]}]}")
                     "scaling"))
      _ (each [_ o (ipairs (spheres n))] (table.insert scene.objects o))
      p (assert (plan.scene->plan scene (plan.renderer-options "llvmpipe"
                                                               {:field-cells (tonumber cells)})))
      source (assert (codegen.shader p :love))
      us (uniforms.pack scene p (camera.from-scene scene) w h)
      f (assert (io.open out :w))]
  (f:write "return {source=[==[" source "]==], uniforms={\n")
  (each [_ u (ipairs us)]
    (f:write "{name=\"" u.name "\", type=\"" u.type "\"")
    (when u.values
      (f:write ", values={" (table.concat (icollect [_ v (ipairs u.values)] (string.format "%.17g" v)) ",") "}"))
    (when u.texture
      (f:write ", texture={width=" u.texture.width ", height=" u.texture.height ", data={")
      ;; (in pieces: a 100,000-sphere field's textures hold millions of floats)
      (let [data u.texture.data]
        (for [i 1 (length data) 4096]
          (f:write (table.concat (fcollect [j i (math.min (length data) (+ i 4095))]
                                   (string.format "%.9g" (. data j))) ",")
                   (if (< (+ i 4095) (length data)) "," ""))))
      (f:write "}}"))
    (f:write "},\n"))
  (f:write "}}\n")
  (f:close))

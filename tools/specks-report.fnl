;; The pictures that leave the app, pixel by pixel (issue 45): for each showcase
;; scene and lighting model, the still that `love . --render` writes by default
;; (adaptive 4 x 4, src/app/quality.fnl) and, with --samples 1, the one-ray picture,
;; against a 4 x 4 supersampled render of the same view, through OSMesa:
;;   unsupported  isolated fireflies the supersampled picture does not support
;;                (fireflies.unsupported, as test/specks_spec.fnl counts them)
;;   specks       pixels more than 40/255 of luma off both their 5 x 5 median and the
;;                supersampled pixel (fireflies.specks)
;;   luajit tools/fnl.lua tools/specks-report.fnl [--size WxH] [--samples 1] [--save DIR] [SCENE ...]
;; --save DIR writes each picture and its supersampled render there as PNG.
;; Prints a line a scene and model, and the worst pixels of each.
(local headless (require :src.backend.headless))
(local scene (require :src.scene.load))
(local plan (require :src.render.plan))
(local camera (require :src.render.camera))
(local quality (require :src.app.quality))
(local fireflies (require :src.verify.fireflies))
(local png (require :src.util.png))
(local {: gpu-render : scene-files} (require :test.support.gpu-check))

(local threshold 40)
(local flat 20)
(local showcase [:city :colonnade :flat :flower :gallery :lighting :machined-part :melt
                 :organic :platonic-shelf :seed :spheres :sundial :twisted-tower])

(fn prepare [file width height model options]
  (let [(s err) (scene.load-file file)
        _ (assert s err)
        opts (collect [k v (pairs options)] k v)]
    (set opts.view :shaded)
    (when model (set opts.model model))
    (let [(p perr) (plan.scene->plan s opts)]
      (assert p perr)
      {:scene s :plan p :cam (camera.from-scene s) : width : height})))

(fn reader [image] (fn [x y] (headless.pixel image x y)))

(fn listing [found]
  (table.concat (icollect [i f (ipairs found) &until (> i 8)]
                  (string.format "(%d,%d) %.0f" f.x f.y f.off))
                " "))

(fn main [...]
  (var [width height] [640 360])
  (var samples nil)
  (var save nil)
  (local files [])
  (let [args [...]]
    (var i 1)
    (while (<= i (length args))
      (case (. args i)
        "--size" (let [(w h) (: (. args (+ i 1)) :match "^(%d+)x(%d+)$")]
                   (set [width height] [(tonumber w) (tonumber h)])
                   (set i (+ i 1)))
        "--save" (do (set save (. args (+ i 1))) (set i (+ i 1)))
        "--samples" (do (set samples (tonumber (. args (+ i 1)))) (set i (+ i 1)))
        f (table.insert files f))
      (set i (+ i 1))))
  (when (= 0 (length files))
    (each [_ name (ipairs showcase)]
      (table.insert files (.. "scenes/" name ".fnl"))))
  (let [(ctx why) (headless.context)
        options (if (= samples 1) {} (quality.still-options))
        totals {:unsupported 0 :specks 0}]
    (assert ctx why)
    (each [_ file (ipairs files)]
      (let [(s) (scene.load-file file)
            models (if (?. s :lighting) [:classic :modern] [false])]
        (each [_ model (ipairs models)]
          (let [t0 (os.clock)
                img (gpu-render ctx (prepare file width height model options)
                                {:prior? (not= samples 1)})
                fine (gpu-render ctx (prepare file width height model {:samples 4}))
                un (fireflies.unsupported width height (reader img) (reader fine) threshold flat)
                sp (fireflies.specks width height (reader img) (reader fine) threshold)]
            (when save
              (let [stem (.. save "/" (: file :match "([^/]+)%.fnl$") "-" (or model "classic"))]
                (png.write-file (.. stem ".png") img)
                (png.write-file (.. stem "-4x4.png") fine)))
            (set totals.unsupported (+ totals.unsupported (length un)))
            (set totals.specks (+ totals.specks (length sp)))
            (print (string.format "%-28s %-8s unsupported %3d  specks %3d  (%.0f s)   %s"
                                  file (or model "classic") (length un) (length sp)
                                  (- (os.clock) t0) (listing sp)))
            (io.stdout:flush)))))
    (print (string.format "total: unsupported %d, specks %d" totals.unsupported totals.specks))))

(main ...)

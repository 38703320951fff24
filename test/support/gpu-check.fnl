;; Shared by the GPU-vs-CPU specs: render a scene's generated :core shader through
;; OSMesa and compare it with the CPU reference marcher on sampled pixels.

(local headless (require :src.backend.headless))
(local scene (require :src.scene.load))
(local plan (require :src.render.plan))
(local camera (require :src.render.camera))
(local codegen (require :src.render.codegen))
(local uniforms (require :src.render.uniforms))
(local reference (require :src.reference))
(local compare (require :src.verify.compare))

;; A pixel passes when its largest channel difference is at most 2/255 (piglit's probe
;; tolerance for floats rounded to 8 bits).
(local tolerance 2)
(local default-size [256 224])
(local sample-options {:grid 16 :extra 256 :step 4 :seed 1})

(fn scene-files [?folder]
  "Every *.fnl file in `?folder` (default scenes/), sorted."
  (let [lfs (require :lfs)
        folder (or ?folder "scenes")
        files (icollect [name (lfs.dir folder)]
                (when (name:match "%.fnl$") (.. folder "/" name)))]
    (table.sort files)
    files))

(fn prepare [file ?options]
  "Scene, plan, camera, sampled pixels and their reference results for `file`.
Options: :view, :render (fields overriding the scene's :render), :size [w h],
:camera (fn [cam] cam) to move the camera, :plan (options for plan.scene->plan),
:seed (the sampled pixels' seed, default 1)."
  (let [options (or ?options {})
        [width height] (or options.size default-size)
        (s err) (scene.load-file file)
        _ (assert s err)
        _ (each [k v (pairs (or options.render {}))] (tset s.render k v))
        (p perr) (plan.scene->plan s (doto (collect [k v (pairs (or options.plan {}))] k v)
                                             (tset :view (or options.view :shaded))))
        _ (assert p perr)
        cam ((or options.camera #$) (camera.from-scene s))
        pixels (compare.sample-pixels s p cam width height
                                      (doto (collect [k v (pairs sample-options)] k v)
                                        (tset :seed (or options.seed sample-options.seed))))]
    {:scene s :plan p :cam cam :pixels pixels : width : height
     :expected (reference.render-pixels s p cam width height pixels)}))

(fn gpu-render [ctx prepared ?options]
  "Render the :core shader of the prepared scene; options :source (fn [text] text)
and :uniforms (fn [list] list) alter the shader text or the uniforms first, :float?
renders into a float target, :prior? draws an adaptive plan as a finished picture
does: its centre rays' picture first, then the picture that reads it
(uniforms.prior)."
  (let [options (or ?options {})
        {:scene s :plan p : cam : width : height} prepared
        source ((or options.source #$) (codegen.shader p :core))
        us ((or options.uniforms #$) (uniforms.pack s p cam width height))
        (program err) (headless.compile ctx source)
        draw (fn [extra]
               (let [(image rerr) (headless.render ctx program
                                                   {: width : height :float? options.float?
                                                    :uniforms (doto (icollect [_ u (ipairs us)] u)
                                                                (#(each [_ u (ipairs extra)]
                                                                    (table.insert $ u))))})]
                 (assert image rerr)
                 image))]
    (assert program err)
    (let [image (if options.prior?
                    (draw (uniforms.prior 2 (draw (uniforms.prior 1))))
                    (draw []))]
      (headless.release ctx program)
      image)))

(fn compare-image [prepared image]
  "Statistics of the GPU image against the reference on the sampled pixels, and the
failing pixels, worst first."
  (let [diffs []
        failing []]
    (each [_ r (ipairs prepared.expected)]
      (let [gpu [(headless.pixel image r.x r.y)]
            cpu (icollect [_ c (ipairs r.color)] (* 255 c))
            d (compare.pixel-diff gpu cpu)]
        (table.insert diffs d)
        (when (> d tolerance)
          (table.insert failing {: d :x r.x :y r.y : gpu : cpu :object r.object
                                 :path (table.concat r.path ",")}))))
    (table.sort failing (fn [a b] (> a.d b.d)))
    (let [st (compare.stats diffs tolerance)]
      (set st.failing failing)
      st)))

(fn passes? [st budget]
  (and (<= st.over budget.over) (<= st.max budget.max)))

(fn describe-failures [label st budget measured?]
  (let [worst (icollect [i f (ipairs st.failing) &until (> i 8)]
                (string.format "  (%d, %d) gpu [%d %d %d] cpu [%.1f %.1f %.1f] diff %.1f object %s path %s"
                               f.x f.y (. f.gpu 1) (. f.gpu 2) (. f.gpu 3)
                               (. f.cpu 1) (. f.cpu 2) (. f.cpu 3) f.d
                               (tostring f.object) f.path))]
    (string.format "%s: %d of %d pixels differ by more than %d/255 (budget %d), max %.1f (budget %g), mean %.2f%s; worst (path: scene index of the object hit by the primary ray and each bounce, -1 = sky):\n%s"
                   label st.over st.count tolerance budget.over st.max budget.max st.mean
                   (if (= measured? false) " (no measured budget for this scene: the default applies)" "")
                   (table.concat worst "\n"))))

(fn report-line [label st]
  (string.format "gpu-vs-cpu %-18s pixels %4d  max %6.1f  mean %5.2f  over %d"
                 label st.count st.max st.mean st.over))

{: tolerance : scene-files : prepare : gpu-render : compare-image : passes?
 : describe-failures : report-line}

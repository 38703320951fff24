;; Specks (issue: "no self-intersection specks"): pixels where a shadow, mirror or
;; occlusion ray meets the surface it leaves. On the GPU (OSMesa), against the CPU
;; reference (double precision) and against a 4 x 4 supersampled render.
(local headless (require :src.backend.headless))
(local scene (require :src.scene.load))
(local plan (require :src.render.plan))
(local camera (require :src.render.camera))
(local reference (require :src.verify.reference))
(local fireflies (require :src.verify.fireflies))
(local {: gpu-render} (require :test.support.gpu-check))

;; As fireflies_spec: a pixel counts when it is more than 40/255 of luma off (a sixth
;; of full scale, twice the largest GPU-vs-CPU difference any scene's budget allows).
(local threshold 40)
(local flat 20)

(fn prepare [file width height ?render ?plan-options]
  (let [(s err) (scene.load-file file)]
    (assert s err)
    (each [k v (pairs (or ?render {}))] (tset s.render k v))
    (let [(p perr) (plan.scene->plan s (doto (collect [k v (pairs (or ?plan-options {}))] k v)
                                         (tset :view :shaded)))]
      (assert p perr)
      {:scene s :plan p :cam (camera.from-scene s) : width : height})))

(fn reader [image]
  (fn [x y] (headless.pixel image x y)))

(fn off-reference [ctx file width height]
  "Pixels of the GPU image of `file` (width x height) whose luma is more than
`threshold` off the CPU reference's, every pixel traced."
  (let [one (prepare file width height)
        read (reader (gpu-render ctx one))
        pixels []]
    (for [y 0 (- height 1)]
      (for [x 0 (- width 1)]
        (table.insert pixels [x y])))
    (icollect [_ r (ipairs (reference.render-pixels one.scene one.plan one.cam width height pixels))]
      (let [[cr cg cb] r.color
            off (math.abs (- (fireflies.luma (read r.x r.y))
                             (fireflies.luma (* 255 cr) (* 255 cg) (* 255 cb))))]
        (when (> off threshold) {:x r.x :y r.y : off})))))

(fn unsupported [ctx file width height ?plan-options]
  "Fireflies of `file` at 1 sample per pixel not supported by its 4 x 4 render (see
fireflies.unsupported)."
  (let [one (prepare file width height {} ?plan-options)
        fine (prepare file width height {:samples 4} ?plan-options)]
    (fireflies.unsupported width height (reader (gpu-render ctx one)) (reader (gpu-render ctx fine))
                           threshold flat)))

(fn listing [found]
  (table.concat (icollect [i f (ipairs found) &until (> i 6)]
                  (string.format "(%d, %d) %.0f off" f.x f.y f.off))
                "; "))

(describe "specks on the GPU"
  (fn []
    (let [(ctx why) (headless.context)]
      (if (not ctx)
          (pending (.. "OSMesa is not available: " (tostring why)))
          (do
            (it "draws the lit face of a plain sphere in organic without a dark spot"
              (fn []
                ;; The issue's green sphere, seen through a 6-degree lens at 160x90
                ;; (pixels as wide as at 1280x720 through a 48-degree one): where the
                ;; light falls along the normal, a soft shadow's first steps measured a
                ;; closest approach of 0 behind the ray's start (float rounding of
                ;; h^2 - y^2) and darkened a patch of 3 pixels (luma 190 -> 60).
                ;; Supersampling keeps the patch (every sample meets it), so the
                ;; reference is the CPU marcher, in double precision.
                (let [found (off-reference ctx "test/fixtures/specks/organic-green-sphere-close.fnl"
                                           160 90)]
                  (assert.are.equal 0 (length found) (listing found)))))
            ;; Every showcase scene, each model it has, at 320x180: a quarter of
            ;; 640x360's pixels, so that the 1 + 16 samples of the 20 runs stay near a
            ;; minute and a half on llvmpipe. `most` is the count of unsupported
            ;; fireflies measured at this size after the soft-shadow fix (the same as
            ;; before it: the fix removed a cluster, which the 4 x 4 render keeps). The
            ;; issue asks for 0 everywhere; the scenes above 0 are open (near misses at
            ;; silhouettes whose normal faces away from the eye, mirror rays starting
            ;; in a crease): these ceilings only keep them from growing.
            (each [_ [file model most] (ipairs [["scenes/city.fnl" :classic 1]
                                                ["scenes/city.fnl" :modern 1]
                                                ["scenes/colonnade.fnl" :classic 7]
                                                ["scenes/colonnade.fnl" :modern 1]
                                                ["scenes/flat.fnl" nil 2]
                                                ["scenes/flower.fnl" :classic 1]
                                                ["scenes/flower.fnl" :modern 1]
                                                ["scenes/gallery.fnl" nil 0]
                                                ["scenes/lighting.fnl" :classic 0]
                                                ["scenes/lighting.fnl" :modern 0]
                                                ["scenes/machined-part.fnl" :classic 7]
                                                ["scenes/machined-part.fnl" :modern 15]
                                                ["scenes/organic.fnl" :classic 0]
                                                ["scenes/organic.fnl" :modern 1]
                                                ["scenes/platonic-shelf.fnl" :classic 1]
                                                ["scenes/platonic-shelf.fnl" :modern 3]
                                                ["scenes/seed.fnl" nil 1]
                                                ["scenes/spheres.fnl" nil 0]
                                                ["scenes/twisted-tower.fnl" :classic 1]
                                                ["scenes/twisted-tower.fnl" :modern 0]])]
              (it (.. "finds at most " most " unsupported fireflies in " file " (" (or model :classic) ") at 320x180")
                (fn []
                  (let [found (unsupported ctx file 320 180 (when model {: model}))]
                    (print (string.format "specks %s (%s): %d unsupported fireflies" file (or model :classic) (length found)))
                    (assert.is_true (<= (length found) most) (listing found)))))))))))

;; Precision far from the origin: a scene moved 1e6 units out on x and z (objects,
;; camera and lights together) must draw as it does at the origin. float32 spacing at
;; 1e6 is 0.0625, so anything the shader computes from world coordinates (a plane's
;; height, a tree object's point, a light's position) rings, speckles or loses its
;; shadows there; everything it sees is made camera-relative on the CPU, in double.
;;
;; Each fixture of test/fixtures/far/ is rendered by the generated GLSL at the origin
;; and moved out, and the two images are compared on the pixels test/gpu_vs_cpu_spec.fnl
;; would sample (a jittered grid plus edge pixels, the same options and size), against
;; that spec's budgets for the nearest scene it measures: the moved scene is allowed
;; to differ from the origin scene as much as the GPU is allowed to differ from the CPU
;; reference, and no more.

(local headless (require :src.backend.headless))
(local load (require :src.scene.load))
(local plan-mod (require :src.render.plan))
(local codegen (require :src.render.codegen))
(local uniforms (require :src.render.uniforms))
(local camera (require :src.render.camera))
(local compare (require :src.verify.compare))
(local images (require :test.support.images))
(local {: tolerance} (require :test.support.gpu-check))

;; gpu_vs_cpu_spec's size and sample options (test/support/gpu-check.fnl).
(local width 256)
(local height 224)
(local sample-options {:grid 16 :extra 256 :step 4 :seed 1})

(local shift [1e6 0 1e6])

;; test/gpu_vs_cpu_spec.fnl's shaded budgets (over: sampled pixels above 2/255; max in
;; 0..255): seed's for the classic kind-grouped scene (mirror bounces flip), the
;; lighting scene's for the modern model, the scene-tree scenes' (organic, colonnade,
;; ...) for tree objects, and its field-beside-a-torus check's for a field.
(local fixtures
  [{:file "test/fixtures/far/seed.fnl" :budget {:over 22 :max 170} :as "seed"}
   {:file "test/fixtures/far/modern.fnl" :budget {:over 2 :max 40} :as "lighting"}
   {:file "test/fixtures/far/tree.fnl" :budget {:over 2 :max 100} :as "the tree scenes"}
   {:file "test/fixtures/far/field.fnl" :budget {:over 2 :max 40} :as "a field"}])

(fn add [[x y z] [dx dy dz]] [(+ x dx) (+ y dy) (+ z dz)])

(fn dot [[ax ay az] [bx by bz]] (+ (* ax bx) (* ay by) (* az bz)))

(fn shifted! [s d]
  "Move loaded scene `s` by `d` in place: camera, classic light, point lights, every
object (a plane's height by its normal's share of `d`). Tree objects of the fixtures
are placed with :pos at their root, or are planes."
  (set s.camera.pos (add s.camera.pos d))
  (set s.light.pos (add s.light.pos d))
  (each [_ l (ipairs (or (?. s :lighting :lights) []))]
    (when l.pos (set l.pos (add l.pos d))))
  (each [_ o (ipairs s.objects)]
    (let [node (or o.tree o)]
      (if (= node.kind :plane)
          (set node.height (+ node.height (dot (or node.normal [0 0 1]) d)))
          (set node.pos (add (assert node.pos (.. o.kind ": no :pos to move")) d)))))
  s)

(fn prepare [file fold? ?d]
  (let [(s err) (load.load-file file)
        _ (assert s err)
        s (if ?d (shifted! s ?d) s)
        p (assert (plan-mod.scene->plan s {:view :shaded : fold?}))
        cam (camera.from-scene s)]
    {:scene s :plan p :cam cam}))

(fn render [ctx {:scene s :plan p : cam}]
  (images.render ctx (codegen.shader p :core) (uniforms.pack s p cam width height)
                 width height))

(fn difference [a b pixels]
  "Statistics (compare.stats) of the channel differences of images `a` and `b` on
`pixels`, and the whole image's largest difference and count over the tolerance."
  (let [diffs (icollect [_ [x y] (ipairs pixels)]
                (compare.pixel-diff [(headless.pixel a x y)] [(headless.pixel b x y)]))
        st (compare.stats diffs tolerance)
        (worst over) (images.channel-difference a b width height)]
    (set st.image-max worst)
    (set st.image-over over)
    st))

(describe "a scene 1e6 units from the origin"
  (fn []
    (let [(ctx why) (headless.context)]
      (if (not ctx)
          (pending (.. "OSMesa is not available: " (tostring why)))
          (each [_ {: file : budget : as} (ipairs fixtures)]
            ;; With the trees' values as uniforms (the player) and folded into the
            ;; code (--render, --export-shader).
            (each [_ fold? (ipairs [false true])]
              (it (.. file (if fold? " folded" "") ": draws as at the origin, within " as
                      "'s GPU-vs-CPU budget")
                (fn []
                  (let [near (prepare file fold?)
                        far (prepare file fold? shift)
                        pixels (compare.sample-pixels near.scene near.plan near.cam width height
                                                      sample-options)
                        st (difference (render ctx near) (render ctx far) pixels)
                        label (.. file (if fold? " folded" ""))]
                    ;; Same shader: moving a scene is a value edit.
                    (assert.are.equal (codegen.shader near.plan :core)
                                      (codegen.shader far.plan :core))
                    (print (string.format "far-origin %-39s pixels %4d  max %6.1f  mean %5.2f  over %d  (whole image: max %.1f, over %d of %d)"
                                          label st.count st.max st.mean st.over
                                          st.image-max st.image-over (* width height)))
                    (assert.is_true (and (<= st.over budget.over) (<= st.max budget.max))
                                    (string.format "%s moved by 1e6: %d of %d sampled pixels differ by more than %d/255 (budget %d), max %.1f (budget %g)"
                                                   label st.over st.count tolerance budget.over
                                                   st.max budget.max)))))))))))

;; The example scenes of vectors (issue 44, examples/) on the GPU: OSMesa's picture of
;; the generated shader, and the app's --render, against the CPU reference marcher,
;; as test/gpu_vs_cpu_spec.fnl checks scenes/ (test/vectors_spec.fnl checks the
;; translation itself).
(local headless (require :src.backend.headless))
(local codegen (require :src.render.codegen))
(local {: prepare : gpu-render : compare-image : passes? : describe-failures : report-line}
       (require :test.support.gpu-check))

;; As test/gpu_vs_cpu_spec.fnl's budgets for scenes/custom.fnl: at most two pixels of
;; the sampled ones more than 2/255 apart (a grazing reflection or shadow edge), none
;; past 40; the normals view at most one, by 3.
(local budgets {:shaded {:over 2 :max 40} :normals {:over 1 :max 3}})

(describe "the example scenes of vectors on the GPU"
  (fn []
    (let [(ctx why) (headless.context)]
      (if (not ctx)
          (pending (.. "OSMesa is not available: " (tostring why)))
          (do
            (each [_ file (ipairs ["examples/polygon-prism.fnl" "examples/vector-box.fnl" "examples/menger-fold.fnl"])]
              (it (.. file ": the GPU picture matches the CPU reference, shaded and normals")
                (fn []
                  (each [_ view (ipairs [:shaded :normals])]
                    (let [budget (. budgets view)
                          prepared (prepare file {: view})
                          st (compare-image prepared (gpu-render ctx prepared))
                          label (.. file " " view)]
                      (print (report-line label st))
                      (assert.is_true (>= st.count 256) (.. label ": only " st.count " pixels sampled"))
                      (assert.is_true (passes? st budget) (describe-failures label st budget)))))))

            (it "a loop with &until draws as the CPU reference draws it (a union of balls that stops inside one)"
              (fn []
                ;; Outside every ball the loop runs to its end, so the picture is the
                ;; one without the stop: this checks the shader's break compiles and
                ;; runs; test/vectors_spec.fnl checks where the stop changes values.
                (let [file "test/out/vectors-until.fnl"]
                  (with-open [f (assert (io.open file :w))]
                    (f:write "(local centres [[0.8 0 0] [0 0.8 0] [-0.8 0 0] [0 -0.8 0] [0 0 0.6]])
{:camera {:pos [0 -5 3] :yaw 90 :pitch 30 :fov 50}
 :light {:pos [-10 -14 20]}
 :objects [{:kind :plane :height -0.6}
           {:kind :custom :color [0.4 0.6 0.9] :bounds [1.3 1.3 1.1]
            :distance (fn [p]
                        (var d 100)
                        (for [i 1 5 &until (< d -0.05)]
                          (set d (math.min d (- (length (- p (. centres i))) 0.5))))
                        d)}]}
"))
                  (each [_ view (ipairs [:shaded :normals])]
                    (let [budget (. budgets view)
                          prepared (prepare file {: view})
                          st (compare-image prepared (gpu-render ctx prepared))
                          label (.. "&until " view)]
                      (print (report-line label st))
                      (assert.is_true (>= st.count 256) (.. label ": only " st.count " pixels sampled"))
                      (assert.is_true (passes? st budget) (describe-failures label st budget)))))))

            (it "the app's --render of the star, one ray a pixel, is the CPU reference's picture"
              (fn []
                (let [png (require :src.util.png)
                      {: love} (require :test.support.app)
                      compare (require :src.verify.compare)
                      (code out) (love "--render examples/polygon-prism.fnl --out test/out/vectors-star.png --size 64x48 --samples 1")
                      _ (assert.are.equal 0 code out)
                      img (assert (png.read-file "test/out/vectors-star.png"))
                      prepared (prepare "examples/polygon-prism.fnl" {:size [64 48]})
                      diffs (icollect [_ r (ipairs prepared.expected)]
                              ;; The PNG's rows from the top, as the sampled pixels'.
                              (let [i (* 4 (+ (* r.y img.width) r.x))]
                                (compare.pixel-diff [(. img.pixels i) (. img.pixels (+ i 1)) (. img.pixels (+ i 2))]
                                                    (icollect [_ c (ipairs r.color)] (* 255 c)))))
                      st (compare.stats diffs 2)]
                  (print (report-line "examples/polygon-prism.fnl through --render" st))
                  (assert.are.same [64 48] [img.width img.height])
                  (assert.is_true (>= st.count 200) (.. "only " st.count " pixels sampled"))
                  (assert.is_true (passes? st budgets.shaded) (.. "over " st.over ", max " st.max)))))

            (it "fails when the shader takes another vertex of the star (the check sees the chain)"
              (fn []
                (let [prepared (prepare "examples/polygon-prism.fnl" {:view :normals})
                      shader (codegen.shader prepared.plan :core)
                      ;; The first item of each chain of the vertices: vertex 1 at
                      ;; counter 2 instead (a fault the CPU reference lacks).
                      (broken n) (shader:gsub "%(v(%d+) == 1%.0%)" "(v%1 == 2.0)")
                      st (compare-image prepared (gpu-render ctx prepared {:source #broken}))]
                  (assert.is_true (> n 0))
                  (print (report-line "polygon-prism, broken chain" st))
                  (assert.is_false (passes? st budgets.normals))))))))))

;; The render settings the accuracy report sweeps (hit test, normal method,
;; over-relaxation, step budget), each checked GPU against CPU on two scenes: the GLSL
;; and the reference implement them independently.
(local headless (require :src.backend.headless))
(local {: prepare : gpu-render : compare-image : passes? : describe-failures : report-line}
  (require :test.support.gpu-check))

;; Budgets as in test/gpu_vs_cpu_spec.fnl (over = sampled pixels above 2/255, max in
;; 0..255 units), measured on llvmpipe at 256x224 with 512 sampled pixels and rounded
;; up. The fixed epsilon (1e-4, the article's) leaves float32 normals a few per cent off
;; tens of units from the camera and bounces amplify that, as in the scene budgets. The
;; scaled hit tests take normals and ray offsets over a step that float32 resolves:
;; measured 0 pixels over and max 0.5-0.6 (seed), 0-2 over and max 0.5-16.4 (spheres);
;; their budgets allow one flipped grazing pixel more than measured, no more.
(local cases
  [;; measured seed 6 over, max 98.0; spheres 9 over, max 21.1
   {:name "fixed, central normals" :render {:normals :central}
    :budgets {:seed {:over 10 :max 110} :spheres {:over 14 :max 50}}}
   ;; measured seed 3 over, max 98.0; spheres 9 over, max 43.8
   {:name "fixed, tetrahedron normals" :render {:normals :tetrahedron}
    :budgets {:seed {:over 8 :max 110} :spheres {:over 14 :max 50}}}
   ;; measured seed 0 over, max 0.6; spheres 2 over, max 16.4
   {:name "relative 1e-4" :render {:hit-test :relative :epsilon 1e-4}
    :budgets {:seed {:over 1 :max 40} :spheres {:over 3 :max 40}}}
   ;; measured 0 over, max 0.5 on both
   {:name "pixel 0.5, tetrahedron" :render {:hit-test :pixel :epsilon 0.5 :normals :tetrahedron}
    :budgets {:seed {:over 1 :max 40} :spheres {:over 1 :max 40}}}
   ;; measured seed 14 over, max 98.0; spheres 30 over, max 43.1 (fixed epsilon again)
   {:name "relaxation 1.5" :render {:relaxation 1.5}
    :budgets {:seed {:over 18 :max 170} :spheres {:over 35 :max 50}}}
   ;; measured 0 over, max 0.5 on both
   {:name "pixel 0.5, relaxation 1.5, 96 steps"
    :render {:hit-test :pixel :epsilon 0.5 :relaxation 1.5 :max-steps 96}
    :budgets {:seed {:over 1 :max 40} :spheres {:over 1 :max 40}}}])

(describe "render settings, GPU against the CPU reference"
  (fn []
    (let [(ctx why) (headless.context)]
      (if (not ctx)
          (pending (.. "OSMesa is not available: " (tostring why)))
          (each [_ c (ipairs cases)]
            (it (.. "agree with " c.name)
              (fn []
                (each [_ name (ipairs [:seed :spheres])]
                  (let [prepared (prepare (.. "scenes/" name ".fnl") {:render c.render})
                        st (compare-image prepared (gpu-render ctx prepared))
                        budget (. c.budgets name)
                        label (.. name ", " c.name)]
                    (print (report-line label st))
                    (assert.is_true (passes? st budget)
                                    (describe-failures label st budget true)))))))))))

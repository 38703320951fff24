;; The GPU-against-CPU budgets of every scene in scenes/ (test/gpu_vs_cpu_spec.fnl,
;; and the tape interpreter's pictures in test/interpret_gpu_spec.fnl).

;; A pixel passes when its largest channel difference is at most 2/255 (piglit's probe
;; tolerance for floats rounded to 8 bits). A scene passes when at most :over sampled
;; pixels fail and no pixel differs by more than :max (in 0..255 units). The GPU is
;; float32 and Mesa re-associates: sphere normals come from float32 differences over
;; epsilon (1e-4) tens of units from the camera, a few per cent off, so mirror bounces
;; move reflected edges and grazing bounces flip between an object and the sky; shadow
;; rays that graze an occluder flip too; step counts differ by a step or two.
;;
;; Measured on llvmpipe (Mesa, LLVM 15), 256x224, 512 sampled pixels (seed 1), and
;; again for sample seeds 2-12 to see how much the figures move with the pixels chosen
;; (a stand-in for another driver's rounding). Each budget is the worst of those 12
;; runs, rounded up a little. Figures: over = pixels above 2/255, max in 0..255.

(local budgets
  {;; seed, shaded: seed 1 gives over 19, max 165.4, mean 2.73 (12 seeds: over 11-21,
   ;; max 64-165). Every failure is a mirror bounce (the big sphere and the plane
   ;; reflecting each other): bright sky against the dark plane is the max. Without
   ;; reflections the whole image is within 3.9/255.
   ;; (Re-measured after the hit and normal code gained distance-scaled steps: seed 1
   ;; gives over 15, max 146.1, mean 1.66.)
   :seed {:shaded {:over 22 :max 170}
          ;; normals: over 0-1, max 2.2 (box and plane normals are exact in float32).
          :normals {:over 2 :max 3}
          ;; glow view: flat colours, exact but for 8-bit rounding (max 0.5).
          :glow {:over 0 :max 1}
          ;; heat: one step of 500 is 2.04/255; over 4-13, max 2.5.
          :heat {:over 14 :max 3}}
   ;; flat, gallery and spheres use the default render settings (a hit test relative
   ;; to the distance travelled, tetrahedron normals, over-relaxation 1.5): normals and
   ;; ray offsets are taken over steps float32 resolves, and the GPU agrees with the
   ;; reference to 8-bit rounding: seed 1 gives over 0 and max 0.5-0.6 in every view
   ;; of flat and gallery, and in the spheres scene one pixel (max 20.2, a bounce
   ;; grazing the floor sphere). The budgets allow one flipped grazing pixel more.
   :flat {:shaded {:over 1 :max 40}
          :normals {:over 1 :max 40}
          :glow {:over 0 :max 1}
          :heat {:over 1 :max 4}}
   :gallery {:shaded {:over 1 :max 40}
             :normals {:over 1 :max 40}
             :glow {:over 0 :max 1}
             :heat {:over 1 :max 4}}
   ;; With bounds (issue 11) two heat pixels of spheres differ by one step (2.3/255):
   ;; the GPU's float32 span starts the march a hair from the reference's.
   :spheres {:shaded {:over 2 :max 40}
             :normals {:over 1 :max 40}
             :glow {:over 0 :max 1}
             :heat {:over 2 :max 4}}
   ;; The scene-tree scenes (issue 9), seed 1: every view within 0.5-0.9/255 but
   ;; for one pixel at most per view: organic shaded (4.4, a shadow ray grazing the
   ;; blended body), and in the heat views of organic, colonnade and flower one
   ;; step of difference (2.3-2.5/255; one step of 500 is 2.04). Budgets: twice the
   ;; flips seen, and a shaded max that allows one grazing shadow flip of a lit
   ;; colour (the scenes' lights halve the lightness in shadow: up to ~100).
   :machined-part {:shaded {:over 2 :max 100} :normals {:over 1 :max 3}
                   :glow {:over 0 :max 1} :heat {:over 2 :max 4}}
   :organic {:shaded {:over 2 :max 100} :normals {:over 1 :max 3}
             :glow {:over 0 :max 1} :heat {:over 2 :max 4}}
   :colonnade {:shaded {:over 2 :max 100} :normals {:over 1 :max 3}
               :glow {:over 0 :max 1} :heat {:over 2 :max 4}}
   :twisted-tower {:shaded {:over 2 :max 100} :normals {:over 1 :max 3}
                   :glow {:over 0 :max 1} :heat {:over 2 :max 4}}
   :flower {:shaded {:over 2 :max 100} :normals {:over 1 :max 3}
            :glow {:over 0 :max 1} :heat {:over 2 :max 4}}
   :platonic-shelf {:shaded {:over 2 :max 100} :normals {:over 1 :max 3}
                    :glow {:over 0 :max 1} :heat {:over 2 :max 4}}
   ;; The modern model (issue 10), seed 1: shaded over 0, max 0.6 with soft shadows,
   ;; occlusion, fog, specular and two Fresnel bounces; normals 0.5, glow 0.4, heat
   ;; 0.5. Budgets: two flipped pixels, as the other tree scenes, but a max of 40:
   ;; soft shadows and occlusion change smoothly, so a grazing flip costs less than a
   ;; hard shadow's; test/lighting_spec.fnl checks that cutting any one feature from
   ;; the GLSL breaks this budget.
   :lighting {:shaded {:over 2 :max 40} :normals {:over 1 :max 3}
              :glow {:over 0 :max 1} :heat {:over 2 :max 4}}
   ;; Custom nodes (issue 30: distance functions written in Fennel, translated to
   ;; GLSL and Lua), modern model, seed 1: shaded over 0, max 0.6; normals 0.5, glow
   ;; 0.5, heat 0.5. Budgets as lighting's.
   :custom {:shaded {:over 2 :max 40} :normals {:over 1 :max 3}
            :glow {:over 0 :max 1} :heat {:over 2 :max 4}}})

;; A scene not measured yet gets these: a few reflection flips at most, exact flat
;; views. Measure it (the test prints its figures) and add it to the table above.
(local default-budgets {:shaded {:over 10 :max 170}
                        :normals {:over 2 :max 3}
                        :glow {:over 0 :max 1}
                        :heat {:over 14 :max 6.5}})

(fn budget-for [name view]
  "The budget of scene `name` in `view`, and whether it was measured (else the
defaults)."
  (let [b (. budgets name)]
    (if (and b (. b view)) (values (. b view) true)
        (values (. default-budgets view) false))))

{: budgets : default-budgets : budget-for}

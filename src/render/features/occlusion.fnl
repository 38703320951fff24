;; Ambient occlusion: the sky's light darkened where surfaces crowd the normal.
(local {: min : max} math)

(fn clamp01 [v] (min 1 (max 0 v)))

{:name :occlusion
 :doc "Ambient occlusion: five distance samples along the normal darken the sky's light."
 :settings {:ao {:type :fraction :default 0.8}          ; strength (0: off)
            :ao-radius {:type :positive :default 0.5}}   ; how far along the normal
 :on? (fn [l] (> l.ao 0))
 :uniforms (fn [l] [{:name "uAo" :type :vec2 :values [l.ao l.ao-radius]}])
 :chunk "shaders/shading/modern/occlusion.glsl"
 :slot :occlusion
 :lines ["occ *= occlusion(p, n);"]
 ;; Its samples as the first turns of the first light's soft shadow march, when the
 ;; scene has one (plan.lighting's :taps): then the slot's lines are not used.
 :taps {:chunk "shaders/shading/modern/occlusion-taps.glsl" :count "kOcclusionTaps"}
 :reach (fn [l] l.ao-radius)
 ;; occlusion() in the chunk: nearer samples weigh more.
 :cpu (fn [l T]
        (fn [px py pz nx ny nz]
          (var occ 0)
          (var weight 1)
          (var total 0)
          (for [i 1 5]
            (let [h (/ (* l.ao-radius i) 5)
                  ;; Read as an estimate of the distance (gEstimate in the chunk).
                  d (T.map-estimate (+ px (* nx h)) (+ py (* ny h)) (+ pz (* nz h)))]
              (set occ (+ occ (* weight (clamp01 (/ (- h d) h)))))
              (set total (+ total weight))
              (set weight (* weight 0.5))))
          (clamp01 (- 1 (/ (* l.ao occ) total)))))}

;; Functions of time, an animated shape: three coloured drops circle a pedestal,
;; bobbing, and melt into each other and into it (a smooth union, whose blend radius
;; breathes and whose materials blend as its distances do), while a twisted column
;; beside them turns. Every moving value is a (fn [t] ...) of the time in seconds:
;; see docs/scenes.md, Functions of time. Space pauses and plays in the player, `.`
;; steps a frame; `love . --record scenes/melt.fnl --out f --frames 120` writes frames.
(local {: sin : cos : pi} math)

(fn orbit [phase radius height]
  ;; A drop's centre: once round the pedestal every 8 s, bobbing twice a turn.
  (fn [t]
    (let [a (+ phase (* (/ pi 4) t))]
      [(* radius (cos a)) (* radius (sin a)) (+ height (* 0.45 (sin (* 2 a))))])))

{:name "melt"
 :camera {:pos [9.5 -8.5 4.4] :yaw 139 :pitch 10 :fov 52}
 :light {:pos [-10 -14 20]}
 ;; The modern look (see docs/scenes.md, Lighting); m in the player shows the classic model.
 :lighting {:lights [{:kind :sun :direction [-0.5 -0.6 0.62] :color [1 0.9 0.78]
                      :intensity 3 :softness 0.05}]
            :sky-zenith [0.42 0.52 0.7] :sky-horizon [0.72 0.8 0.9]
            :ambient 0.5 :ao 0.8 :ao-radius 0.5 :exposure 1.1}
 :render {:reflections 1 :draw-distance 200}
 :objects
 [{:kind :plane :height 0 :color [0.42 0.4 0.38] :roughness 0.8}
  {:kind :smooth-union :radius (fn [t] (+ 0.55 (* 0.2 (sin (* 0.9 t)))))
   :color [0.85 0.84 0.8] :roughness 0.35
   :children [{:kind :round-box :size [2.2 2.2 1.6] :radius 0.12 :pos [0 0 0.8]}
              {:kind :sphere :radius 0.75 :pos (orbit 0 1.25 2.2)
               :color [0.9 0.25 0.15] :roughness 0.25}
              {:kind :sphere :radius 0.65 :pos (orbit (* 2 (/ pi 3)) 1.25 2.2)
               :color [0.95 0.7 0.15] :roughness 0.25}
              {:kind :sphere :radius 0.55 :pos (orbit (* 4 (/ pi 3)) 1.25 2.2)
               :color [0.2 0.45 0.9] :roughness 0.25}]}
  ;; A twisted column that turns (its :rotate is a function of time).
  {:kind :twist :angle 35 :pos [-3.2 2.6 0] :rotate (fn [t] [0 0 (* 30 t)])
   :color [0.3 0.7 0.55] :roughness 0.3
   :children [{:kind :round-box :size [1.1 1.1 4.4] :radius 0.08 :pos [0 0 2.2]}]}
  ;; A chrome ball that reflects the moving drops.
  {:kind :sphere :radius 0.9 :pos [2.6 2.9 0.9] :color [0.92 0.92 0.95] :mirror 1
   :roughness 0.05}]}

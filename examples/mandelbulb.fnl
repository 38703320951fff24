;; The Mandelbulb of power 8, as on Shadertoy (issue 44): z -> z^8 + p in spherical
;; coordinates, the point as one vector, a loop that stops with &until once the orbit
;; escapes, and Hubbard and Douady's distance estimate 0.5 log(r) r / dr.
;;   SDL_VIDEODRIVER=offscreen love . --render examples/mandelbulb.fnl --out bulb.png
(local {: sin : cos : atan : log : max} math)

;; The distance estimate of the bulb at point p: r is |z| and dr the derivative's
;; length, carried along the orbit (dr -> 8 r^7 dr + 1). Past r = 2 the orbit
;; escapes, so the loop stops there; 8 turns are enough for a picture. The angle from
;; the z axis is atan(|z.xy|, z.z), not acos(z.z / r): GLSL's acos is coarse on some
;; drivers (llvmpipe's moved the GPU's distance 1.7e-2 from the CPU's; atan, 3e-6),
;; and 8 theta multiplies its error. The orbit of the origin stays at 0, where log 0
;; is no number: r is kept off 0.
(fn mandelbulb [p]
  (var z p)
  (var dr 1)
  (var r (max (length p) 1e-9))
  (for [i 1 8 &until (> r 2)]
    (let [theta (* 8 (atan (length [(. z 1) (. z 2)]) (. z 3)))
          phi (* 8 (atan (. z 2) (. z 1)))
          zr (^ r 8)]
      (set dr (+ (* 8 (^ r 7) dr) 1))
      (set z (+ (* zr [(* (sin theta) (cos phi)) (* (sin theta) (sin phi)) (cos theta)]) p))
      (set r (max (length z) 1e-9))))
  (* 0.5 (log r) (/ r dr)))

{:name "mandelbulb"
 :camera {:pos [2 -5.4 2.4] :yaw 110 :pitch 22 :fov 52}
 :light {:pos [-10 -14 20]}
 :lighting {:lights [{:kind :sun :direction [-0.5 -0.6 0.65] :color [1 0.9 0.75]
                      :intensity 3 :softness 0.04}]
            :sky-zenith [0.2 0.32 0.6] :sky-horizon [0.75 0.72 0.8]
            :ambient 0.6 :ao 0.9 :ao-radius 0.25}
 :render {:reflections 0 :draw-distance 100}
 :objects
 [{:kind :plane :height -1.2 :color [0.42 0.45 0.5]}
  ;; A fractal's distance estimate is no distance at scales below the detail of its
  ;; last turn (8^-8 of a unit): there it changes by hundreds per unit (the loader
  ;; measures 498 outside the bulb; a ray divided by 1.1 times that runs out of its
  ;; 500 steps near the bulb). Shadertoy marches it as it is, and so does this: the
  ;; factor 1 is declared and trusted (test/examples_spec.fnl checks that no ray
  ;; runs out of steps, test/examples_gpu_spec.fnl the GPU's picture).
  {:kind :custom :color [0.9 0.62 0.36] :roughness 0.5
   :lipschitz 1 :trust-lipschitz true
   :distance (fn [p] (mandelbulb p))
   :bounds [1.2 1.2 1.2]}]}

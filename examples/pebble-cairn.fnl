;; A cairn of pebbles, each IQ's ellipsoid bound, as on Shadertoy (issue 44): the
;; stones' centres and radii are arrays of the file, read in a loop by its counter.
;;   SDL_VIDEODRIVER=offscreen love . --render examples/pebble-cairn.fnl --out cairn.png
(local {: min} math)

;; Five stones, bottom to top: centre, and radii along x y z.
(local centres [[0 0 0.26] [0.08 -0.04 0.68] [-0.05 0.05 1.0] [0.03 0 1.26] [0 0.02 1.45]])
(local radii [[0.78 0.6 0.27] [0.58 0.44 0.2] [0.42 0.34 0.15] [0.3 0.24 0.12] [0.16 0.14 0.08]])

;; IQ's bound of the ellipsoid of radii r: k0 (k0 - 1) / k1, a bound (not the
;; distance), whose slope the loader measures.
(fn sd-ellipsoid [p r]
  (let [k0 (length (/ p r))
        k1 (length (/ p (* r r)))]
    (/ (* k0 (- k0 1)) k1)))

{:name "pebble-cairn"
 :camera {:pos [4 -5.6 2] :yaw 126 :pitch 10 :fov 45}
 :light {:pos [-10 -14 20]}
 :lighting {:lights [{:kind :sun :direction [-0.5 -0.3 0.6] :color [1 0.85 0.68]
                      :intensity 3 :softness 0.07}]
            :sky-zenith [0.35 0.5 0.78] :sky-horizon [0.92 0.85 0.75]
            :ambient 0.5 :ao 0.9 :ao-radius 0.3}
 :render {:reflections 0 :draw-distance 100}
 :objects
 [{:kind :plane :height 0 :color [0.45 0.52 0.38]}
  {:kind :custom :color [0.62 0.6 0.56] :roughness 0.8
   :distance (fn [p]
               (var d math.huge)
               (for [i 1 5]
                 (set d (min d (sd-ellipsoid (- p (. centres i)) (. radii i)))))
               d)
   :bounds [0.8 0.65 1.55]}]}

;; Specular highlights: each light's Blinn-Phong term, weighted by Schlick's Fresnel.
(local {: sqrt : max : min} math)

(fn clamp01 [v] (min 1 (max 0 v)))

(fn mix [a b w] (+ (* a (- 1 w)) (* b w)))

{:name :specular
 :doc "Specular highlights: Blinn-Phong per light, energy-normalised, with Schlick's Fresnel."
 :settings {:specular {:type :boolean :default true}}
 :on? (fn [l] (= true l.specular))
 :uniforms (fn [] [])
 :chunk "shaders/shading/modern/specular.glsl"
 :slot :light
 :lines ["c += specularLight(n, l, v, albedo, mirror, roughness, radiance);"]
 ;; specularLight() in the chunk.
 :cpu (fn [_l _T]
        (fn [s lx ly lz lr lg lb]
          (let [[nx ny nz] s.n
                [vx vy vz] s.v
                [ar ag ab] s.albedo
                hx (+ lx vx) hy (+ ly vy) hz (+ lz vz)
                len (sqrt (+ (* hx hx) (* hy hy) (* hz hz)))
                (hx hy hz) (if (> len 0) (values (/ hx len) (/ hy len) (/ hz len)) (values 0 0 1))
                shininess (math.pow 2 (+ 1 (* 10 (- 1 s.roughness))))
                f0 (mix 0.04 1 s.mirror)
                fresnel (+ f0 (* (- 1 f0)
                                 (math.pow (- 1 (clamp01 (+ (* lx hx) (* ly hy) (* lz hz)))) 5)))
                spec (* fresnel (/ (+ shininess 8) 8)
                        (math.pow (clamp01 (+ (* nx hx) (* ny hy) (* nz hz))) shininess))]
            (values (* lr (mix 1 ar s.mirror) spec)
                    (* lg (mix 1 ag s.mirror) spec)
                    (* lb (mix 1 ab s.mirror) spec)))))}

;; Fog: each segment of a path loses light to it exponentially in its density, thinning
;; with height (Quilez's closed form), and takes on its colour, tinted toward a sun.
(local {: linear} (require :src.render.color))

(local {: exp : max : abs} math)

(fn mix [a b w] (+ (* a (- 1 w)) (* b w)))

{:name :fog
 :doc "Fog: exponential in its density, thinning with height, tinted toward each sun."
 :settings {:fog {:type :fog :default 0}                    ; density per unit (0: off)
            :fog-color {:type :color :default [0.75 0.85 0.95]}
            :fog-falloff {:type :fog :default 0}}           ; thinning per unit of height
 :on? (fn [l] (> l.fog 0))
 :uniforms (fn [l cam-pos]
             [{:name "uFog" :type :vec4 :values (doto (linear l.fog-color) (table.insert l.fog))}
              {:name "uFogFalloff" :type :float :values [l.fog-falloff]}
              {:name "uCamHeight" :type :float :values [(. cam-pos 3)] :view? true}])
 :chunk "shaders/shading/modern/fog.glsl"
 :slot :segment
 :lines ["float fogThrough = fogTransmittance(origin, dir, t);"
         "through *= fogThrough;"
         "radiance += weight * ((1.0 - fogThrough) * fogColor(dir));"]
 ;; fogTransmittance() and fogColor() in the chunk.
 :cpu (fn [l _T]
        (let [[fr fg fb] (linear l.fog-color)
              fog-max (max fr fg fb)
              suns (icollect [_ light (ipairs l.lights)]
                     (when (= light.kind :sun)
                       (let [[r g b] (linear light.color light.intensity)
                             m (max r g b 0.000001)]
                         {:dir light.direction :tint [(/ r m) (/ g m) (/ b m)]})))]
          (fn [_ox _oy oz dx dy dz t]
            (let [k (* l.fog-falloff dz t)
                  thinning (if (> (abs k) 0.0001) (/ (- 1 (exp (- k))) k) 1)
                  through (exp (- (* l.fog (exp (- (* l.fog-falloff oz))) t thinning)))]
              (var (r g b) (values fr fg fb))
              (each [_ sun (ipairs suns)]
                (let [[lx ly lz] sun.dir
                      [tr tg tb] sun.tint
                      w (math.pow (max (+ (* dx lx) (* dy ly) (* dz lz)) 0) 8)]
                  (set (r g b) (values (mix r (* tr fog-max) w) (mix g (* tg fog-max) w)
                                       (mix b (* tb fog-max) w)))))
              (let [f (- 1 through)]
                (values through (* f r) (* f g) (* f b)))))))}

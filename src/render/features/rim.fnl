;; Rim light: a surface seen edge-on takes the sky's light, as a back light outlines a
;; figure. It shows that a feature takes one file and its chunk, nothing else
;; (docs/how-it-works.md, Lighting features).
{:name :rim
 :doc "Rim light: surfaces seen edge-on glow with the sky's light along their normal."
 :settings {:rim {:type :fraction :default 0}             ; strength (0: off)
            :rim-power {:type :positive :default 3}}      ; higher: a thinner rim
 :on? (fn [l] (> l.rim 0))
 :uniforms (fn [l] [{:name "uRim" :type :vec2 :values [l.rim l.rim-power]}])
 :chunk "shaders/shading/modern/rim.glsl"
 :slot :surface
 :lines ["surface += rimLight(cosView, albedo, skyLight);"]
 ;; rimLight() in the chunk.
 :cpu (fn [l _T]
        (fn [s]
          (let [k (* l.rim (math.pow (- 1 s.cos-view) l.rim-power))
                [ar ag ab] s.albedo
                [sr sg sb] s.sky]
            (values (* k ar sr) (* k ag sg) (* k ab sb)))))}

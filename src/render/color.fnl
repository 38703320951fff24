;; Colours: scene files write them as picked (sRGB); the shaders light in linear light.

(fn linear [[r g b] ?k]
  "An sRGB colour in linear light (the shader's gamma of 2.2), times `?k`."
  (let [k (or ?k 1)]
    [(* k (math.pow r 2.2)) (* k (math.pow g 2.2)) (* k (math.pow b 2.2))]))

{: linear}

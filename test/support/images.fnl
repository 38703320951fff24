;; Rendering a shader headless (src/backend/headless.fnl) and comparing two images
;; pixel by pixel.

(local headless (require :src.backend.headless))

(fn render [ctx source us width height]
  "The image of fragment shader `source` with uniforms `us` at `width` x `height`."
  (let [program (assert (headless.compile ctx source))
        image (assert (headless.render ctx program {: width : height :uniforms us}))]
    (headless.release ctx program)
    image))

(fn channel-difference [image-a image-b width height]
  "The largest channel difference (0-255) between images `image-a` and `image-b` of `width` x
`height`, and how many pixels differ by more than 2/255 in some channel."
  (var worst 0)
  (var over 0)
  (for [y 0 (- height 1)]
    (for [x 0 (- width 1)]
      (let [[r g b] [(headless.pixel image-a x y)]
            [r2 g2 b2] [(headless.pixel image-b x y)]
            d (math.max (math.abs (- r r2)) (math.abs (- g g2)) (math.abs (- b b2)))]
        (set worst (math.max worst d))
        (when (> d 2) (set over (+ over 1))))))
  (values worst over))

{: render : channel-difference}

;; Fireflies: single pixels brighter (or darker) than every one of their eight
;; neighbours by more than a set amount. A true image can have such a pixel only for
;; a feature smaller than a pixel; a marcher makes them when a normal taken across an
;; edge sends a bounce or a highlight the wrong way. Pure: works on any image given
;; as width, height and a pixel reader.

(fn luma [r g b]
  ;; Rec. 709 weights on the stored (display) values, 0..255.
  (+ (* 0.2126 r) (* 0.7152 g) (* 0.0722 b)))

(fn find [width height read threshold]
  "Pixels of a width x height image (read: (fn [x y]) -> r g b, 0..255) whose luma is
above the brightest of its eight neighbours, or below the darkest, by more than
`threshold` (0..255). Border pixels are not judged. Returns a list of {:x :y :by},
`by` the margin, largest first."
  (let [out []]
    (for [y 1 (- height 2)]
      (for [x 1 (- width 2)]
        (let [l (luma (read x y))]
          (var lo math.huge)
          (var hi (- math.huge))
          (for [dy -1 1]
            (for [dx -1 1]
              (when (or (not= dx 0) (not= dy 0))
                (let [n (luma (read (+ x dx) (+ y dy)))]
                  (when (< n lo) (set lo n))
                  (when (> n hi) (set hi n))))))
          (let [by (math.max (- l hi) (- lo l))]
            (when (> by threshold)
              (table.insert out {: x : y : by}))))))
    (table.sort out (fn [a b] (> a.by b.by)))
    out))

(fn rgba-reader [image]
  "A pixel reader for {:width :height :pixels} with RGBA bytes, row 0 at the top
(0-based FFI arrays, as png.decode and the headless renderer give)."
  (let [{: width : pixels} image]
    (fn [x y]
      (let [i (* 4 (+ x (* y width)))]
        (values (. pixels i) (. pixels (+ i 1)) (. pixels (+ i 2)))))))

(fn unsupported [width height read read-fine threshold flat]
  "Fireflies of an image (read) judged against a supersampled render of the same view
(read-fine): isolated pixels (see `find`) whose luma is also more than `threshold`
off the supersampled pixel's, where the supersampled image is flat around it (its
3 x 3 luma range under `flat`): the true image is smooth there, so no sub-pixel
feature explains the pixel. Returns {:x :y :by :off} like `find`'s."
  (let [lf (fn [x y] (luma (read-fine x y)))]
    (icollect [_ p (ipairs (find width height read threshold))]
      (let [off (math.abs (- (luma (read p.x p.y)) (lf p.x p.y)))]
        (var lo math.huge)
        (var hi (- math.huge))
        (for [dy -1 1]
          (for [dx -1 1]
            (let [v (lf (+ p.x dx) (+ p.y dy))]
              (set lo (math.min lo v))
              (set hi (math.max hi v)))))
        (when (and (> off threshold) (< (- hi lo) flat))
          {:x p.x :y p.y :by p.by : off})))))

(fn median-5x5 [width height lf x y]
  ;; The median luma of the 5 x 5 pixels around (x, y), those inside the image.
  (let [vs []]
    (for [dy -2 2]
      (for [dx -2 2]
        (let [px (+ x dx) py (+ y dy)]
          (when (and (>= px 0) (< px width) (>= py 0) (< py height))
            (table.insert vs (lf px py))))))
    (table.sort vs)
    (. vs (+ 1 (math.floor (/ (length vs) 2))))))

(fn specks [width height read read-fine threshold]
  "Speck pixels of an image (read) against a supersampled render of the same view
(read-fine): pixels whose luma is more than `threshold` off both the median of their
5 x 5 neighbourhood and the supersampled pixel's. A speck no larger than a few pixels
stands out from its median; the supersampled render says whether the true image has
it (a sub-pixel glint does, averaged). Unlike `unsupported`, a speck needs not be a
single pixel, nor its surroundings flat. Returns {:x :y :off :median} (off from the
supersampled pixel), largest first."
  (let [lf (fn [x y] (luma (read x y)))
        out []]
    (for [y 0 (- height 1)]
      (for [x 0 (- width 1)]
        (let [l (lf x y)
              fine (luma (read-fine x y))]
          (when (> (math.abs (- l fine)) threshold)
            (let [m (median-5x5 width height lf x y)]
              (when (> (math.abs (- l m)) threshold)
                (table.insert out {: x : y :off (math.abs (- l fine)) :median m})))))))
    (table.sort out (fn [a b] (> a.off b.off)))
    out))

{: find : unsupported : specks : rgba-reader : luma}

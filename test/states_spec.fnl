;; tier: fast
;; Specs for src/verify/states.fnl, the classifier of tools/check-states.sh: synthetic
;; pictures of one state (lit, shadowed, partly undrawn, upscaled) pass; pictures whose
;; bands come from two states are flagged; X window dumps decode.
(local ffi (require :ffi))
(local states (require :src.verify.states))

(fn colour-of [value]
  ;; The test/states scenes' colour for :hue `value` (fully saturated, hue 240 * value).
  (let [d (* 240 value)
        f (fn [n] (let [k (% (+ n (/ d 60)) 6)]
                    (- 1 (math.max 0 (math.min k (- 4 k) 1)))))]
    [(f 5) (f 3) (f 1)]))

(fn picture [width height value-at]
  "An image whose pixel (x, y) is the colour of (value-at x y), lit by a brightness
that falls from 1 at the top to 0.25 at the bottom, with a dark shadow square and a
grey, unsaturated text-like box; value-at may return nil for a black (undrawn) pixel."
  (let [pixels (ffi.new "uint8_t[?]" (* width height 4))]
    (for [y 0 (- height 1)]
      (for [x 0 (- width 1)]
        (let [d (* 4 (+ x (* y width)))
              v (value-at x y)
              light (- 1 (* 0.75 (/ y height)))
              light (if (and (< 20 x 40) (< 30 y 50)) 0.08 light)
              grey? (and (< 60 x 90) (< 5 y 15))
              c (if (not v) [0 0 0] grey? [0.6 0.6 0.6] (colour-of v))
              k (if grey? 1 light)]
          (for [i 1 3]
            (tset pixels (+ d i -1) (math.floor (+ 0.5 (* 255 k (. c i))))))
          (tset pixels (+ d 3) 255))))
    {: width : height : pixels}))

(fn upscaled [image factor]
  "image shrunk by factor (box filter) and stretched back with bilinear filtering."
  (let [{: width : height : pixels} image
        sw (math.floor (/ width factor))
        sh (math.floor (/ height factor))
        small (fcollect [i 1 (* sw sh 3)] 0)
        out (ffi.new "uint8_t[?]" (* width height 4))]
    (for [sy 0 (- sh 1)]
      (for [sx 0 (- sw 1)]
        (for [c 0 2]
          (var sum 0)
          (for [y 0 (- factor 1)]
            (for [x 0 (- factor 1)]
              (set sum (+ sum (. pixels (+ c (* 4 (+ (* sx factor) x (* width (+ (* sy factor) y))))))))))
          (tset small (+ 1 c (* 3 (+ sx (* sy sw)))) (/ sum (* factor factor))))))
    (for [y 0 (- height 1)]
      (for [x 0 (- width 1)]
        (let [fx (math.max 0 (math.min (- sw 1.001) (- (/ (+ x 0.5) factor) 0.5)))
              fy (math.max 0 (math.min (- sh 1.001) (- (/ (+ y 0.5) factor) 0.5)))
              x0 (math.floor fx)
              y0 (math.floor fy)
              ax (- fx x0)
              ay (- fy y0)
              at (fn [xx yy c] (. small (+ 1 c (* 3 (+ xx (* yy sw))))))]
          (for [c 0 2]
            (tset out (+ c (* 4 (+ x (* y width))))
                  (math.floor (+ 0.5 (* (- 1 ay) (+ (* (- 1 ax) (at x0 y0 c)) (* ax (at (+ x0 1) y0 c))))
                                 (* ay (+ (* (- 1 ax) (at x0 (+ y0 1) c)) (* ax (at (+ x0 1) (+ y0 1) c))))))))
          (tset out (+ 3 (* 4 (+ x (* y width)))) 255))))
    {: width : height :pixels out}))

(fn xwd-of [image]
  "An X window dump, as `xwd` writes it on a 24-bit TrueColor screen (LSB-first 32-bit
pixels, blue in the low byte), of image."
  (let [be (fn [n] (string.char (% (math.floor (/ n 16777216)) 256) (% (math.floor (/ n 65536)) 256)
                                (% (math.floor (/ n 256)) 256) (% n 256)))
        {: width : height : pixels} image
        name "test\000"
        fields [(+ 100 (length name)) 7 2 24 width height 0 0 32 0 32 32 (* 4 width) 5
                0xff0000 0xff00 0xff 8 256 2 width height 0 0 0]
        header (.. (table.concat (icollect [_ f (ipairs fields)] (be f))) name)
        colours (string.rep "\000" (* 12 2))
        rows (fcollect [i 0 (- (* width height) 1)]
               (string.char (. pixels (+ 2 (* 4 i))) (. pixels (+ 1 (* 4 i))) (. pixels (* 4 i)) 0))]
    (.. header colours (table.concat rows))))

(describe "states"
  (fn []
    (it "reads a pixel's hue and skips grey, dark and black pixels"
      (fn []
        (assert.are.equal 0 (states.pixel-hue 255 0 0))
        (assert.are.equal 120 (states.pixel-hue 0 255 0))
        (assert.are.equal 240 (states.pixel-hue 0 0 255))
        (assert.is_true (< (math.abs (- (* -60 (/ 42 255)) (states.pixel-hue 255 0 42))) 1e-9))
        (assert.is_nil (states.pixel-hue 128 128 128))
        (assert.is_nil (states.pixel-hue 30 10 0))
        (assert.is_nil (states.pixel-hue 0 0 0))))

    (it "passes a lit, shadowed picture of one state, whole or partly undrawn"
      (fn []
        (each [_ v (ipairs [0 0.1 0.45 0.9 1])]
          (let [r (states.classify (picture 120 80 (fn [] v)) {:strips 8 :step 1})]
            (assert.is_false r.mixed?)
            (assert.is_true (< r.spread 1))
            (assert.is_true (< (math.abs (- (states.hue->value r.hue) v)) 0.01))))
        ;; The bottom half not drawn yet (black): those strips have no state.
        (let [r (states.classify (picture 120 80 (fn [_ y] (when (< y 40) 0.3))) {:strips 8 :step 1})]
          (assert.is_false r.mixed?)
          (assert.is_nil (. r.strips 8 :hue)))))

    (it "passes a coarse picture of one state upscaled with linear filtering"
      (fn []
        (let [image (upscaled (picture 128 80 (fn [] 0.6)) 8)
              r (states.classify image {:strips 8 :step 1})]
          (assert.is_false r.mixed?)
          (assert.is_true (< r.spread 1)))))

    (it "flags a picture whose bands come from two states"
      (fn []
        (let [r (states.classify (picture 120 80 (fn [_ y] (if (< y 50) 0.5 0.55)))
                                 {:strips 8 :step 1})]
          (assert.is_true r.mixed?)
          (assert.is_true (< (math.abs (- r.spread 12)) 1)))
        ;; A band 4 rows tall, one strip of the default height.
        (let [r (states.classify (picture 120 80 (fn [_ y] (if (<= 40 y 43) 0.5 0.55))))]
          (assert.is_true r.mixed?))
        ;; States 0.02 apart (4.8 degrees) are within the tolerance.
        (let [r (states.classify (picture 120 80 (fn [_ y] (if (< y 50) 0.5 0.52)))
                                 {:strips 8 :step 1})]
          (assert.is_false r.mixed?))))

    (it "classifies only the region asked for"
      (fn []
        ;; A panel of another colour at the top right is left out by :x1.
        (let [image (picture 120 80 (fn [x y] (if (and (>= x 40) (< y 20)) 0.8 0.2)))]
          (assert.is_true (. (states.classify image {:strips 8 :step 1}) :mixed?))
          (assert.is_false (. (states.classify image {:strips 8 :step 1 :x1 40}) :mixed?)))))

    (it "decodes an X window dump to the same pixels"
      (fn []
        (let [image (picture 24 10 (fn [x] (/ x 24)))
              decoded (states.decode-xwd (xwd-of image))]
          (assert.are.equal 24 decoded.width)
          (assert.are.equal 10 decoded.height)
          (var same true)
          (for [i 0 (- (* 24 10 4) 1)]
            (when (not= (. image.pixels i) (. decoded.pixels i)) (set same false)))
          (assert.is_true same))
        (let [(none why) (states.decode-xwd "short")]
          (assert.is_nil none)
          (assert.are.equal "too short for an XWD header" why))))))

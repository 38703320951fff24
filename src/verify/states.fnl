;; Does a picture show one scene state, or parts of several? For the scenes in
;; test/states/, whose every surface and sky takes one colour whose hue encodes the
;; state (lighting changes only brightness), the state can be read from any part of
;; the picture: the picture is cut into horizontal strips, each strip's state is the
;; median hue of its coloured pixels, and a picture whose strips disagree by more than
;; a tolerance mixes states. A blurry (upscaled) or partly drawn picture of one state
;; passes: blending colours of one hue keeps the hue, and undrawn black or grey pixels
;; carry no hue and are skipped. Pure (LuaJIT): images are {:width :height :pixels},
;; pixels 8-bit RGBA, row 0 at the top, as src/util/png.fnl decodes them; read-xwd
;; reads the window dumps of `xwd`, which grabs a 1280x720 window in ~15 ms where
;; ImageMagick's `import` takes 0.6-0.8 s on the test machine.

(local ffi (require :ffi))
(local bit (require :bit))

;; Degrees of hue over a parameter going from 0 to 1: test/states/*.fnl map their
;; :hue parameter from red (0) to blue (240), short of the wrap at 360.
(local hue-span 240)

;; A pixel's hue is trusted only when its chroma (max - min of its 0-255 channels) is
;; at least this: 8-bit rounding moves the hue by up to 60 * 0.5 / chroma degrees,
;; under 1 degree here. Dark shadow and black (undrawn) pixels fall below it.
(local min-chroma 40)

;; A strip with fewer coloured pixels than this share of those sampled has no state
;; (a strip covered by text or not drawn yet): it is left out, not guessed.
(local min-share 0.2)

;; Strips whose median hues differ by more than this many degrees mix states. Measured
;; (`tools/check-states.sh --calibrate`): single-state renders of test/states/hue.fnl
;; at 1280x720 for six :hue values, whole and shrunk to 160x90 then stretched back with
;; linear filtering, have a strip spread of at most 0.5 degree (one histogram bin); so
;; do the unmixed frames the player showed in the check (at most 1 degree while the
;; animated hue runs). 6 is twelve bins, and under every step the scenarios take: a slider
;; step of the drag is 9.6 degrees, the edits move 48 to 72, and the animated hue
;; moves 6 degrees in 0.125 s.
(local tolerance 6)

;; Rows per strip: a player may draw bands of a few rows (up to 256 bands in 720
;; rows), and a band less than half a strip tall would not move the strip's median.
;; Sampling every other row and column, a strip of 4 rows of 960 pixels has 960
;; samples, plenty for a median.
(local strip-rows 4)

(local bins-per-degree 2)
(local hue-min -60)    ; hues above 300 are taken as negative (reds near 360)
(local hue-max 300)

(fn pixel-hue [r g b]
  "The hue in degrees (-60 to 300) of the 0-255 colour r g b, or nil when its chroma
is under min-chroma (grey, dark or black)."
  (let [mx (math.max r g b)
        mn (math.min r g b)
        c (- mx mn)]
    (when (>= c min-chroma)
      (let [h (if (= mx r) (* 60 (/ (- g b) c))
                  (= mx g) (* 60 (+ 2 (/ (- b r) c)))
                  (* 60 (+ 4 (/ (- r g) c))))]
        (if (> h hue-max) (- h 360) (< h hue-min) (+ h 360) h)))))

(fn histogram-median [counts total]
  ;; The centre of the bin holding the middle sample.
  (var seen 0)
  (var found nil)
  (for [i 0 (- (length counts) 1) &until found]
    (set seen (+ seen (. counts (+ i 1))))
    (when (>= seen (/ total 2))
      (set found (+ hue-min (/ (+ i 0.5) bins-per-degree)))))
  found)

(fn strip-hues [image opts]
  "The state of each horizontal strip of `image`: a sequence of {:y0 :y1 :hue
:share}, :hue the median hue (degrees) of the strip's coloured pixels, nil when
under min-share of them are coloured. opts (all optional): :strips (one per
strip-rows rows), the region
:x0 :x1 :y0 :y1 (the whole image; x1, y1 exclusive) and :step (2: every other pixel
of every other row is sampled)."
  (let [{: width : height : pixels} image
        opts (or opts {})
        x0 (or opts.x0 0)
        x1 (math.min width (or opts.x1 width))
        ry0 (or opts.y0 0)
        ry1 (math.min height (or opts.y1 height))
        n (or opts.strips (math.max 1 (math.floor (/ (- ry1 ry0) strip-rows))))
        step (or opts.step 2)
        nbins (* bins-per-degree (- hue-max hue-min))]
    (fcollect [s 1 n]
      (let [y0 (+ ry0 (math.floor (/ (* (- s 1) (- ry1 ry0)) n)))
            y1 (+ ry0 (math.floor (/ (* s (- ry1 ry0)) n)))
            counts (fcollect [_ 1 nbins] 0)]
        (var sampled 0)
        (var coloured 0)
        (for [y y0 (- y1 1) step]
          (for [x x0 (- x1 1) step]
            (let [d (* 4 (+ x (* y width)))
                  h (pixel-hue (. pixels d) (. pixels (+ d 1)) (. pixels (+ d 2)))]
              (set sampled (+ sampled 1))
              (when h
                (let [b (+ 1 (math.min (- nbins 1)
                                       (math.floor (* bins-per-degree (- h hue-min)))))]
                  (tset counts b (+ (. counts b) 1))
                  (set coloured (+ coloured 1)))))))
        (let [share (if (> sampled 0) (/ coloured sampled) 0)]
          {: y0 : y1 : share
           :hue (when (and (> coloured 0) (>= share min-share))
                  (histogram-median counts coloured))})))))

(fn classify [image opts]
  "Whether `image` shows one state: {:strips (see strip-hues) :lo :hi :spread :hue
:mixed?}, lo and hi the least and greatest strip hues, spread their difference, hue
the median strip hue (the state shown; nil when no strip has one) and mixed? true
when spread exceeds opts.tolerance (default `tolerance` degrees)."
  (let [strips (strip-hues image opts)
        hues (icollect [_ s (ipairs strips)] s.hue)
        limit (or (?. opts :tolerance) tolerance)]
    (table.sort hues)
    (if (= 0 (length hues))
        {: strips :spread 0 :mixed? false}
        (let [lo (. hues 1)
              hi (. hues (length hues))]
          {: strips : lo : hi :spread (- hi lo)
           :hue (. hues (math.ceil (/ (length hues) 2)))
           :mixed? (> (- hi lo) limit)}))))

(fn hue->value [hue]
  "The :hue parameter value (0 to 1) of the test/states scenes that gives `hue`."
  (/ hue hue-span))

(fn value->hue [value]
  "The hue in degrees the test/states scenes give the :hue parameter `value`."
  (* value hue-span))

(fn u32 [bytes i big?]
  ;; The unsigned 32-bit number at byte i (1-based) of the string bytes.
  (let [(a b c d) (string.byte bytes i (+ i 3))]
    (if big?
        (+ (* a 16777216) (* b 65536) (* c 256) d)
        (+ (* d 16777216) (* c 65536) (* b 256) a))))

(fn mask-shift [mask]
  ;; How far right to shift a pixel so that `mask`'s lowest bit lands at bit 0.
  (var s 0)
  (while (and (< s 32) (= 0 (bit.band mask (bit.lshift 1 s))))
    (set s (+ s 1)))
  s)

(fn decode-xwd [bytes]
  "Decode an X window dump (what `xwd` writes) of a 24-bit TrueColor window, 32 bits
per pixel, into {:width :height :pixels} (8-bit RGBA, an FFI array). nil + reason
for any other kind of dump."
  (if (< (length bytes) 100) (values nil "too short for an XWD header")
      (let [f (fn [k] (u32 bytes (+ 1 (* 4 k)) true))
            header-size (f 0)
            version (f 1)
            format (f 2)
            width (f 4)
            height (f 5)
            byte-order (f 7)
            bits-per-pixel (f 11)
            bytes-per-line (f 12)
            visual-class (f 13)
            masks [(f 14) (f 15) (f 16)]
            ncolors (f 19)
            data-start (+ header-size (* 12 ncolors))]
        (if (not= version 7) (values nil (.. "XWD version " version ", expected 7"))
            (not= format 2) (values nil "not a ZPixmap dump")
            (not= bits-per-pixel 32) (values nil (.. bits-per-pixel " bits per pixel, expected 32"))
            (and (not= visual-class 4) (not= visual-class 5))
            (values nil "not a TrueColor or DirectColor visual")
            (< (length bytes) (+ data-start (* bytes-per-line height)))
            (values nil "truncated pixel data")
            (let [pixels (ffi.new "uint8_t[?]" (* width height 4))
                  src (ffi.cast "const uint8_t *" bytes)
                  shifts (icollect [_ m (ipairs masks)] (mask-shift m))
                  big? (= byte-order 1)]
              (for [y 0 (- height 1)]
                (for [x 0 (- width 1)]
                  (let [o (+ data-start (* y bytes-per-line) (* 4 x))
                        v (if big?
                              (bit.bor (bit.lshift (. src o) 24) (bit.lshift (. src (+ o 1)) 16)
                                       (bit.lshift (. src (+ o 2)) 8) (. src (+ o 3)))
                              (bit.bor (bit.lshift (. src (+ o 3)) 24) (bit.lshift (. src (+ o 2)) 16)
                                       (bit.lshift (. src (+ o 1)) 8) (. src o)))
                        d (* 4 (+ x (* y width)))]
                    (for [c 1 3]
                      (tset pixels (+ d c -1)
                            (bit.band 255 (bit.rshift (bit.band v (. masks c)) (. shifts c)))))
                    (tset pixels (+ d 3) 255))))
              {: width : height : pixels})))))

(fn read-xwd [path]
  "Read and decode the X window dump at path; nil + \"path: reason\" on failure."
  (case (io.open path :rb)
    (nil err) (values nil err)
    f (let [bytes (f:read :*a)]
        (f:close)
        (case (decode-xwd (or bytes ""))
          image image
          (nil why) (values nil (.. path ": " why))))))

{: pixel-hue : strip-hues : classify : hue->value : value->hue : decode-xwd : read-xwd
 : tolerance : min-chroma : hue-span}

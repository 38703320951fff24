;; PNG encode/decode (8-bit RGBA and RGB, non-interlaced) in LuaJIT FFI over zlib, for screenshots and test images.
(local ffi (require :ffi))
(local libc (require :src.util.libc))
(local bit (require :bit))

(local signature "\137PNG\r\n\026\n")

(var zlib nil)

(fn z []
  "The zlib library, loaded and declared on first use."
  (when (= nil zlib)
    (set zlib (assert (libc.library [:z :libz.so.1]
                                    [:compressBound :compress2 :uncompress :crc32]))))
  zlib)

(fn crc [s]
  "CRC-32 of the Lua string s, as a number."
  (tonumber ((. (z) :crc32) 0 s (length s))))

(fn u32-be [n]
  (string.char (bit.band (bit.rshift n 24) 0xFF) (bit.band (bit.rshift n 16) 0xFF)
               (bit.band (bit.rshift n 8) 0xFF) (bit.band n 0xFF)))

(fn read-u32 [s i]
  "Big-endian unsigned 32-bit integer at 1-based offset i of s."
  (let [(a b c d) (string.byte s i (+ i 3))]
    (+ (* a 16777216) (* b 65536) (* c 256) d)))

(fn chunk [kind data]
  (let [body (.. kind data)]
    (.. (u32-be (length data)) body (u32-be (crc body)))))

(fn paeth [a b c]
  (let [p (- (+ a b) c)
        pa (math.abs (- p a))
        pb (math.abs (- p b))
        pc (math.abs (- p c))]
    (if (and (<= pa pb) (<= pa pc)) a
        (<= pb pc) b
        c)))

(fn filter-for [filter y]
  (if (= nil filter) 0
      (= (type filter) :number) filter
      (. filter (+ 1 (% y (length filter))))))

(fn encode [image]
  "Encode {:width :height :pixels} as a PNG string.
pixels is a Lua sequence (1-based) or an FFI uint8 array (0-based) of
width*height*4 RGBA bytes, row 0 = top row. Options: :alpha? false writes
8-bit RGB (alpha dropped); :filter is a filter type 0-4 for every row, or a
sequence of filter types used for successive rows (cycled)."
  (let [{: width : height : pixels : filter} image
        alpha? (not= false image.alpha?)
        channels (if alpha? 4 3)
        n (* width height 4)]
    (assert (and (= (type width) :number) (>= width 1) (= width (math.floor width)))
            "png.encode: width must be a positive integer")
    (assert (and (= (type height) :number) (>= height 1) (= height (math.floor height)))
            "png.encode: height must be a positive integer")
    (assert (or (= (type pixels) :cdata) (= (type pixels) :table))
            "png.encode: pixels must be a Lua sequence or an FFI uint8 array")
    (when (= (type pixels) :table)
      (assert (= (length pixels) n)
              (string.format "png.encode: expected %d pixel bytes, got %d" n (length pixels))))
    (let [offset (if (= (type pixels) :table) 1 0)
          row-bytes (* width channels)
          stride (+ 1 row-bytes)
          raw-size (* height stride)
          raw (ffi.new "uint8_t[?]" raw-size)
          ;; unfiltered rows: current and previous
          cur (ffi.new "uint8_t[?]" row-bytes)
          prev (ffi.new "uint8_t[?]" row-bytes)]
      (for [y 0 (- height 1)]
        (for [x 0 (- width 1)]
          (let [src (+ offset (* 4 (+ x (* y width))))
                dst (* x channels)]
            (for [c 0 (- channels 1)]
              (tset cur (+ dst c) (. pixels (+ src c))))))
        (let [f (filter-for filter y)
              base (* y stride)
              prev-row? (> y 0)]
          (assert (and (= (type f) :number) (>= f 0) (<= f 4) (= f (math.floor f)))
                  "png.encode: filter must be 0-4")
          (tset raw base f)
          (for [i 0 (- row-bytes 1)]
            (let [v (. cur i)
                  a (if (>= i channels) (. cur (- i channels)) 0)
                  b (if prev-row? (. prev i) 0)
                  c (if (and prev-row? (>= i channels)) (. prev (- i channels)) 0)
                  pred (case f
                         0 0
                         1 a
                         2 b
                         3 (bit.rshift (+ a b) 1)
                         4 (paeth a b c))]
              (tset raw (+ base 1 i) (bit.band (- v pred) 0xFF)))))
        (ffi.copy prev cur row-bytes))
      (let [lib (z)
            out-len (ffi.new "unsigned long[1]" (lib.compressBound raw-size))
            out (ffi.new "uint8_t[?]" (. out-len 0))
            rc (lib.compress2 out out-len raw raw-size 6)]
        (assert (= rc 0) (.. "png.encode: zlib compress2 failed with code " rc))
        (.. signature
            (chunk :IHDR (.. (u32-be width) (u32-be height)
                             (string.char 8 (if alpha? 6 2) 0 0 0)))
            (chunk :IDAT (ffi.string out (tonumber (. out-len 0))))
            (chunk :IEND ""))))))

(fn parse-chunks [bytes]
  "Split a PNG string into {:ihdr data :idat concatenated} or nil + reason."
  (if (not= (bytes:sub 1 8) signature)
      (values nil "not a PNG (bad signature)")
      (let [len (length bytes)
            idat []]
        (var pos 9)
        (var ihdr nil)
        (var plte nil)
        (var trns nil)
        (var done? false)
        (var err nil)
        (while (and (not done?) (not err))
          (if (> (+ pos 11) len)
              (set err "truncated (no IEND chunk)")
              (let [size (read-u32 bytes pos)
                    kind (bytes:sub (+ pos 4) (+ pos 7))
                    body-end (+ pos 7 size)]
                (if (> (+ body-end 4) len)
                    (set err (.. "truncated in " kind " chunk"))
                    (not (kind:match "^%a%a%a%a$"))
                    (set err "corrupt chunk header")
                    (not= (crc (bytes:sub (+ pos 4) body-end))
                          (read-u32 bytes (+ body-end 1)))
                    (set err (.. "CRC mismatch in " kind " chunk"))
                    (let [data (bytes:sub (+ pos 8) body-end)]
                      (if (= kind :IHDR) (set ihdr data)
                          (= kind :IDAT) (table.insert idat data)
                          (= kind :IEND) (set done? true)
                          (= kind :PLTE) (set plte data)
                          (= kind :tRNS) (set trns data)
                          (kind:match "^%u")
                          (set err (.. "unsupported critical chunk " kind)))
                      (when (and (= nil ihdr) (not= kind :IHDR))
                        (set err (.. "first chunk is " kind ", expected IHDR")))
                      (set pos (+ body-end 5)))))))
        (if err (values nil err)
            (= nil ihdr) (values nil "missing IHDR chunk")
            (not= (length ihdr) 13) (values nil "bad IHDR length")
            (= 0 (length idat)) (values nil "missing IDAT chunk")
            {: ihdr : plte : trns :idat (table.concat idat)}))))

(fn unfilter [data height stride bpp]
  "Undo the per-row filters of data in place; nil + reason on a bad filter byte."
  (let [row-bytes (- stride 1)]
    (var err nil)
    (for [y 0 (- height 1) &until err]
      (let [base (+ 1 (* y stride))
            up (- base stride)
            f (. data (- base 1))
            prev-row? (> y 0)]
        (case f
          0 nil
          1 (for [i bpp (- row-bytes 1)]
              (tset data (+ base i) (bit.band (+ (. data (+ base i)) (. data (+ base i (- bpp)))) 0xFF)))
          2 (when prev-row?
              (for [i 0 (- row-bytes 1)]
                (tset data (+ base i) (bit.band (+ (. data (+ base i)) (. data (+ up i))) 0xFF))))
          3 (for [i 0 (- row-bytes 1)]
              (let [a (if (>= i bpp) (. data (+ base i (- bpp))) 0)
                    b (if prev-row? (. data (+ up i)) 0)]
                (tset data (+ base i) (bit.band (+ (. data (+ base i)) (bit.rshift (+ a b) 1)) 0xFF))))
          4 (for [i 0 (- row-bytes 1)]
              (let [a (if (>= i bpp) (. data (+ base i (- bpp))) 0)
                    b (if prev-row? (. data (+ up i)) 0)
                    c (if (and prev-row? (>= i bpp)) (. data (+ up i (- bpp))) 0)]
                (tset data (+ base i) (bit.band (+ (. data (+ base i)) (paeth a b c)) 0xFF))))
          _ (set err (string.format "bad filter type %d on row %d" f y)))))
    (if err (values nil err) true)))

(local channel-counts {0 1 2 3 3 1 4 2 6 4})
(local allowed-depths {0 {1 true 2 true 4 true 8 true 16 true} 2 {8 true 16 true}
                       3 {1 true 2 true 4 true 8 true} 4 {8 true 16 true}
                       6 {8 true 16 true}})

(fn sample-reader [data stride depth channels]
  "A function (y x c) -> the 8-bit value of channel c of pixel x on row y (16-bit
samples keep their high byte; packed 1/2/4-bit samples come back unscaled)."
  (if (= depth 8)
      (fn [y x c] (. data (+ 1 (* y stride) (* x channels) c)))
      (= depth 16)
      (fn [y x c] (. data (+ 1 (* y stride) (* 2 (+ (* x channels) c)))))
      (let [per-byte (/ 8 depth)
            mask (- (bit.lshift 1 depth) 1)]
        (fn [y x _c]
          (let [byte (. data (+ 1 (* y stride) (math.floor (/ x per-byte))))
                shift (- 8 (* depth (+ 1 (% x per-byte))))]
            (bit.band (bit.rshift byte shift) mask))))))

(fn expand! [pixels width height colour depth read palette alpha]
  ;; Every colour type to 8-bit RGBA.
  (let [grey-scale (if (< depth 8) (/ 255 (- (bit.lshift 1 depth) 1)) 1)]
    (for [y 0 (- height 1)]
      (for [x 0 (- width 1)]
        (let [d (* 4 (+ x (* y width)))]
          (case colour
            6 (for [c 0 3] (tset pixels (+ d c) (read y x c)))
            2 (do (for [c 0 2] (tset pixels (+ d c) (read y x c)))
                  (tset pixels (+ d 3) 255))
            0 (let [g (math.floor (+ 0.5 (* grey-scale (read y x 0))))]
                (for [c 0 2] (tset pixels (+ d c) g))
                (tset pixels (+ d 3) 255))
            4 (let [g (read y x 0)]
                (for [c 0 2] (tset pixels (+ d c) g))
                (tset pixels (+ d 3) (read y x 1)))
            3 (let [i (read y x 0)]
                (for [c 0 2] (tset pixels (+ d c) (or (. palette (+ (* 3 i) c 1)) 0)))
                (tset pixels (+ d 3) (or (and alpha (. alpha (+ i 1))) 255)))))))))

(fn decode [bytes]
  "Decode a PNG string into {:width :height :pixels}, pixels an FFI uint8_t
array of width*height*4 RGBA bytes with row 0 = top row. Accepts every
non-interlaced PNG: greyscale, RGB, palette (with tRNS alpha), greyscale+alpha and
RGBA, at every bit depth the format allows (16-bit samples keep their high byte).
Returns nil + reason on malformed or unsupported input."
  (if (not= (type bytes) :string)
      (values nil "png.decode: expected a string")
      (let [(parts err) (parse-chunks bytes)]
        (if (not parts) (values nil err)
            (let [ihdr parts.ihdr
                  width (read-u32 ihdr 1)
                  height (read-u32 ihdr 5)
                  (depth colour compression filter-method interlace) (string.byte ihdr 9 13)
                  channels (. channel-counts colour)]
              (if (or (= width 0) (= height 0)) (values nil "zero image size")
                  (> (* width height) 0x10000000) (values nil "image too large")
                  (= nil channels)
                  (values nil (string.format "invalid colour type %d" colour))
                  (not (. allowed-depths colour depth))
                  (values nil (string.format "invalid bit depth %d for colour type %d" depth colour))
                  (and (= colour 3) (= nil parts.plte))
                  (values nil "palette image without a PLTE chunk")
                  (not= compression 0) (values nil "unknown compression method")
                  (not= filter-method 0) (values nil "unknown filter method")
                  (not= interlace 0) (values nil "interlaced PNGs are not supported")
                  (let [bits (* channels depth)
                        stride (+ 1 (math.ceil (/ (* width bits) 8)))
                        bpp (math.max 1 (/ bits 8))
                        expected (* height stride)
                        data (ffi.new "uint8_t[?]" (+ expected 1))
                        out-len (ffi.new "unsigned long[1]" (+ expected 1))
                        idat parts.idat
                        rc ((. (z) :uncompress) data out-len idat (length idat))]
                    (if (not= rc 0)
                        (values nil (string.format "corrupt image data (zlib error %d)" rc))
                        (not= (tonumber (. out-len 0)) expected)
                        (values nil (string.format "image data is %d bytes, expected %d"
                                                   (tonumber (. out-len 0)) expected))
                        (let [(ok why) (unfilter data height stride (math.floor bpp))]
                          (if (not ok) (values nil why)
                              (let [pixels (ffi.new "uint8_t[?]" (* width height 4))
                                    palette (when parts.plte [(string.byte parts.plte 1 -1)])
                                    alpha (when (and parts.trns (= colour 3))
                                            [(string.byte parts.trns 1 -1)])]
                                (expand! pixels width height colour depth
                                         (sample-reader data stride depth channels)
                                         palette alpha)
                                {: width : height : pixels})))))))))))

(fn read-file [path]
  "Read and decode the PNG file at path; nil + \"path: reason\" on failure."
  (let [(f err) (io.open path :rb)]
    (if (not f) (values nil err)
        (let [bytes (f:read :*a)]
          (f:close)
          (let [(image why) (decode (or bytes ""))]
            (if image image (values nil (.. path ": " why))))))))

(fn write-file [path image]
  "Encode image (see encode) and write it to path; true, or nil + \"path: reason\"."
  (let [bytes (encode image)
        (f err) (io.open path :wb)]
    (if (not f) (values nil err)
        (let [(ok why) (f:write bytes)]
          (f:close)
          (if ok true (values nil (.. path ": " (tostring why))))))))

{: encode : decode : read-file : write-file}

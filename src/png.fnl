;; PNG encode/decode (8-bit RGBA and RGB, non-interlaced) in LuaJIT FFI over zlib, for screenshots and test images.
(local ffi (require :ffi))
(local bit (require :bit))

(local signature "\137PNG\r\n\026\n")

(local zlib-cdefs
       ["unsigned long compressBound(unsigned long sourceLen);"
        "int compress2(uint8_t *dest, unsigned long *destLen, const uint8_t *source, unsigned long sourceLen, int level);"
        "int uncompress(uint8_t *dest, unsigned long *destLen, const uint8_t *source, unsigned long sourceLen);"
        "unsigned long crc32(unsigned long crc, const uint8_t *buf, unsigned int len);"])

(var zlib nil)

(fn z []
  "The zlib library, loaded and declared on first use."
  (when (= nil zlib)
    (each [_ decl (ipairs zlib-cdefs)]
      ;; Another module may already have declared the same function.
      (pcall ffi.cdef decl))
    (let [(ok lib) (pcall ffi.load :z)]
      (set zlib (if ok lib (ffi.load :libz.so.1)))))
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
                          (= kind :PLTE) nil
                          (kind:match "^%u")
                          (set err (.. "unsupported critical chunk " kind)))
                      (when (and (= nil ihdr) (not= kind :IHDR))
                        (set err (.. "first chunk is " kind ", expected IHDR")))
                      (set pos (+ body-end 5)))))))
        (if err (values nil err)
            (= nil ihdr) (values nil "missing IHDR chunk")
            (not= (length ihdr) 13) (values nil "bad IHDR length")
            (= 0 (length idat)) (values nil "missing IDAT chunk")
            {: ihdr :idat (table.concat idat)}))))

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

(fn decode [bytes]
  "Decode a PNG string into {:width :height :pixels}, pixels an FFI uint8_t
array of width*height*4 RGBA bytes with row 0 = top row. Accepts 8-bit RGBA
and 8-bit RGB (alpha set to 255), non-interlaced. Returns nil + reason on
malformed or unsupported input."
  (if (not= (type bytes) :string)
      (values nil "png.decode: expected a string")
      (let [(parts err) (parse-chunks bytes)]
        (if (not parts) (values nil err)
            (let [ihdr parts.ihdr
                  width (read-u32 ihdr 1)
                  height (read-u32 ihdr 5)
                  (depth colour compression filter-method interlace) (string.byte ihdr 9 13)
                  channels (case colour 6 4 2 3 _ nil)
                  colour-names {0 "greyscale" 3 "palette" 4 "greyscale+alpha"}]
              (if (or (= width 0) (= height 0)) (values nil "zero image size")
                  (> (* width height) 0x10000000) (values nil "image too large")
                  (= nil channels)
                  (values nil (string.format "unsupported colour type %d (%s); only RGBA (6) and RGB (2) are supported"
                                             colour (or (. colour-names colour) "invalid")))
                  (not= depth 8)
                  (values nil (string.format "unsupported bit depth %d; only 8 is supported" depth))
                  (not= compression 0) (values nil "unknown compression method")
                  (not= filter-method 0) (values nil "unknown filter method")
                  (not= interlace 0) (values nil "interlaced PNGs are not supported")
                  (let [stride (+ 1 (* width channels))
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
                        (let [(ok why) (unfilter data height stride channels)]
                          (if (not ok) (values nil why)
                              (let [pixels (ffi.new "uint8_t[?]" (* width height 4))]
                                (if (= channels 4)
                                    (for [y 0 (- height 1)]
                                      (ffi.copy (+ pixels (* y width 4))
                                                (+ data 1 (* y stride)) (* width 4)))
                                    (for [y 0 (- height 1)]
                                      (let [src (+ 1 (* y stride))
                                            dst (* y width 4)]
                                        (for [x 0 (- width 1)]
                                          (let [s (+ src (* x 3))
                                                d (+ dst (* x 4))]
                                            (tset pixels d (. data s))
                                            (tset pixels (+ d 1) (. data (+ s 1)))
                                            (tset pixels (+ d 2) (. data (+ s 2)))
                                            (tset pixels (+ d 3) 255))))))
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

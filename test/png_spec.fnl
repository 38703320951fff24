;; tier: fast
;; Specs for src/util/png.fnl: round trips, every filter type, RGB input and rejection of bad files.
(local ffi (require :ffi))
(local bit (require :bit))
(local png (require :src.util.png))

(fn random-pixels [n seed]
  (math.randomseed seed)
  (fcollect [_ 1 n] (math.random 0 255)))

(fn same-pixels? [expected actual n]
  "True when the Lua sequence expected matches the 0-based FFI array actual for n bytes."
  (var ok true)
  (for [i 0 (- n 1) &until (not ok)]
    (when (not= (. expected (+ i 1)) (. actual i))
      (set ok false)))
  ok)

(local crc-table
       (fcollect [n 0 255]
         (do
           (var c n)
           (for [_ 1 8]
             (set c (if (= 1 (bit.band c 1))
                        (bit.bxor 0xEDB88320 (bit.rshift c 1))
                        (bit.rshift c 1))))
           c)))

(fn crc32 [s]
  "Plain Lua CRC-32, independent of zlib's."
  (var c 0xFFFFFFFF)
  (for [i 1 (length s)]
    (set c (bit.bxor (. crc-table (+ 1 (bit.band (bit.bxor c (s:byte i)) 0xFF)))
                     (bit.rshift c 8))))
  (let [v (bit.bnot c)]
    (if (< v 0) (+ v 4294967296) v)))

(fn u32-be [n]
  (string.char (bit.band (bit.rshift n 24) 0xFF) (bit.band (bit.rshift n 16) 0xFF)
               (bit.band (bit.rshift n 8) 0xFF) (bit.band n 0xFF)))

(fn patch-ihdr [bytes depth colour]
  "Rewrite the IHDR bit depth and colour type of a PNG string, fixing its CRC."
  (let [data (.. (bytes:sub 17 24) (string.char depth colour) (bytes:sub 27 29))
        body (.. :IHDR data)]
    (.. (bytes:sub 1 12) body (u32-be (crc32 body)) (bytes:sub 34))))

(fn small-png []
  (png.encode {:width 5 :height 4 :pixels (random-pixels 80 7)}))

(describe "png"
  (fn []
    (it "round-trips seeded random images given as Lua sequences"
      (fn []
        (each [seed [w h] (ipairs [[1 1] [2 3] [17 5] [64 48] [3 100]])]
          (let [n (* w h 4)
                pixels (random-pixels n seed)
                image (png.decode (png.encode {:width w :height h : pixels}))]
            (assert.are.equal w image.width)
            (assert.are.equal h image.height)
            (assert.is_true (same-pixels? pixels image.pixels n))))))

    (it "round-trips FFI uint8 arrays"
      (fn []
        (let [w 31 h 9 n (* w h 4)
              pixels (random-pixels n 99)
              arr (ffi.new "uint8_t[?]" n)]
          (for [i 0 (- n 1)] (tset arr i (. pixels (+ i 1))))
          (let [image (png.decode (png.encode {:width w :height h :pixels arr}))]
            (assert.is_true (same-pixels? pixels image.pixels n))))))

    (it "writes the expected header"
      (fn []
        (let [bytes (small-png)]
          (assert.are.equal "\137PNG\r\n\026\n" (bytes:sub 1 8))
          (assert.are.equal :IHDR (bytes:sub 13 16))
          (assert.are.equal (u32-be 5) (bytes:sub 17 20))
          (assert.are.equal (u32-be 4) (bytes:sub 21 24))
          (assert.are.equal (string.char 8 6 0 0 0) (bytes:sub 25 29))
          (assert.are.equal (crc32 (bytes:sub 13 29)) (+ (* 16777216 (bytes:byte 30)) (* 65536 (bytes:byte 31))
                                                         (* 256 (bytes:byte 32)) (bytes:byte 33))))))

    (it "decodes each filter type (0-4) applied to every row"
      (fn []
        (for [f 0 4]
          (let [w 23 h 11 n (* w h 4)
                pixels (random-pixels n (+ 1000 f))
                bytes (png.encode {:width w :height h : pixels :filter f})
                image (png.decode bytes)]
            (assert.is_truthy image)
            (assert.is_true (same-pixels? pixels image.pixels n))))))

    (it "decodes rows mixing all filter types, smooth and noisy content"
      (fn []
        (let [w 40 h 30 n (* w h 4)
              noisy (random-pixels n 3)
              smooth (fcollect [i 0 (- n 1)]
                       (let [p (math.floor (/ i 4)) x (% p w) y (math.floor (/ p w))]
                         (% (case (% i 4) 0 (* x 6) 1 (* y 8) 2 (+ x y) 3 (- 255 x)) 256)))]
          (each [_ pixels (ipairs [noisy smooth])]
            (let [image (png.decode (png.encode {:width w :height h : pixels
                                                 :filter [4 0 1 2 3 4 4 2 2 3 1 0]}))]
              (assert.is_true (same-pixels? pixels image.pixels n)))))))

    (it "expands 8-bit RGB to RGBA with alpha 255"
      (fn []
        (let [w 13 h 7 n (* w h 4)
              pixels (random-pixels n 11)
              bytes (png.encode {:width w :height h : pixels :alpha? false :filter [0 1 2 3 4]})
              image (png.decode bytes)]
          (assert.are.equal 2 (bytes:byte 26))
          (for [i 0 (- n 1)]
            (assert.are.equal (if (= 3 (% i 4)) 255 (. pixels (+ i 1)))
                              (. image.pixels i))))))

    (it "rejects a wrong signature"
      (fn []
        (let [(image err) (png.decode (.. "\137PNX" (: (small-png) :sub 5)))]
          (assert.is_nil image)
          (assert.matches "signature" err))
        (let [(image err) (png.decode "")]
          (assert.is_nil image)
          (assert.matches "signature" err))
        (let [(image err) (png.decode 42)]
          (assert.is_nil image)
          (assert.is_string err))))

    (it "rejects truncated files at every length"
      (fn []
        (let [bytes (small-png)]
          (for [len 8 (- (length bytes) 1)]
            (let [(image err) (png.decode (bytes:sub 1 len))]
              (assert.is_nil image)
              (assert.is_string err))))
        (let [(_ err) (png.decode (: (small-png) :sub 1 40))]
          (assert.matches "truncated" err))))

    (it "rejects a bad CRC"
      (fn []
        (let [bytes (small-png)
              i 45 ; inside the IDAT data
              flipped (string.char (bit.bxor (bytes:byte i) 0x01))
              (image err) (png.decode (.. (bytes:sub 1 (- i 1)) flipped (bytes:sub (+ i 1))))]
          (assert.is_nil image)
          (assert.matches "CRC mismatch in IDAT" err))))

    (it "rejects invalid colour types and bit depths with a clear message"
      (fn []
        (let [bytes (small-png)]
          (assert.are.equal :table (type (png.decode (patch-ihdr bytes 8 6))))
          (let [(image err) (png.decode (patch-ihdr bytes 8 3))]
            (assert.is_nil image)
            (assert.are.equal "palette image without a PLTE chunk" err))
          (let [(image err) (png.decode (patch-ihdr bytes 8 5))]
            (assert.is_nil image)
            (assert.are.equal "invalid colour type 5" err))
          (let [(image err) (png.decode (patch-ihdr bytes 4 6))]
            (assert.is_nil image)
            (assert.are.equal "invalid bit depth 4 for colour type 6" err)))))

    (it "decodes every colour type and bit depth to RGBA"
      (fn []
        ;; LÖVE's encoder picks the smallest form for an image (a palette for a few
        ;; colours), so goldens come in all of these. Fixtures: test/fixtures/png/,
        ;; made with Python's zlib, and the RGBA each pixel must give.
        (let [fennel (require :fennel)
              expected (fennel.dofile "test/fixtures/png/expected.fnl")]
          (each [_ name (ipairs [:grey1 :grey2 :grey4 :grey8 :grey16 :palette2 :palette8
                                 :grey-alpha8 :rgba16])]
            (let [image (assert (png.read-file (.. "test/fixtures/png/" name ".png")))
                  want (. expected name)]
              (assert.are.equal 5 image.width)
              (assert.are.equal 2 image.height)
              (for [k 0 9]
                (assert.are.same (. want (+ k 1))
                                 [(. image.pixels (* 4 k)) (. image.pixels (+ (* 4 k) 1))
                                  (. image.pixels (+ (* 4 k) 2)) (. image.pixels (+ (* 4 k) 3))]
                                 (.. name " pixel " k))))))))
    (it "writes and reads files"
      (fn []
        (let [path (os.tmpname)
              pixels (random-pixels (* 6 5 4) 21)]
          (assert.is_true (png.write-file path {:width 6 :height 5 : pixels}))
          (let [image (png.read-file path)]
            (assert.are.equal 6 image.width)
            (assert.is_true (same-pixels? pixels image.pixels (* 6 5 4))))
          (let [f (io.open path :wb)]
            (f:write "not a png")
            (f:close))
          (let [(image err) (png.read-file path)]
            (assert.is_nil image)
            (assert.are.equal (.. path ": not a PNG (bad signature)") err))
          (os.remove path))
        (let [(image err) (png.read-file "/nonexistent/dir/x.png")]
          (assert.is_nil image)
          (assert.matches "^/nonexistent/dir/x.png: " err))
        (let [(ok err) (png.write-file "/nonexistent/dir/x.png" {:width 1 :height 1 :pixels [1 2 3 4]})]
          (assert.is_nil ok)
          (assert.matches "^/nonexistent/dir/x.png: " err))))

    (it "treats malformed arguments to encode as programmer errors"
      (fn []
        (assert.has_error (fn [] (png.encode {:width 2 :height 2 :pixels [1 2 3]})))
        (assert.has_error (fn [] (png.encode {:width 0 :height 2 :pixels []})))
        (assert.has_error (fn [] (png.encode {:width 1 :height 1 :pixels [1 2 3 4] :filter 5})))))))

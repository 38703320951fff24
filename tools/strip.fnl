;; Join PNG frames of the same size side by side into one strip (for the docs):
;;   luajit tools/fnl.lua tools/strip.fnl OUT.png IN1.png IN2.png ...
(local png (require :src.util.png))
(local out-path (. arg 1))
(local imgs (fcollect [i 2 (length arg)] (assert (png.read-file (. arg i)))))
(local w (. imgs 1 :width))
(local h (. imgs 1 :height))
(local n (length imgs))
(local ffi (require :ffi))
(local pixels (ffi.new "uint8_t[?]" (* w n h 4)))
(each [k img (ipairs imgs)]
  (for [y 0 (- h 1)]
    (for [x 0 (- w 1)]
      (for [c 0 3]
        (tset pixels (+ (* 4 (+ (* y w n) (* (- k 1) w) x)) c) (. img.pixels (+ (* 4 (+ (* y w) x)) c)))))))
(assert (png.write-file out-path {:width (* w n) :height h : pixels}))

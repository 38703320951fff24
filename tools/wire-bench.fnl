;; Times src/util/wire.fnl on 100,000 sphere objects (about 1.3 million numbers):
;; encode, decode, and the size of the bytes. Not a test (timings on a busy machine
;; vary); run it by hand: luajit tools/fnl.lua tools/wire-bench.fnl [count]

(local wire (require :src.util.wire))

(local count (or (tonumber (. arg 1)) 100000))

(fn sphere [i]
  {:kind "sphere"
   :pos [(* i 0.5) (math.sin i) (- (* i 0.25))]
   :radius (+ 0.5 (* (% i 7) 0.1))
   :color [(% (* i 0.13) 1) (% (* i 0.29) 1) (% (* i 0.71) 1)]
   :mirror 0.1})

(local scene {:name "bench" :objects (fcollect [i 1 count] (sphere i))})

(fn best-of [n f]
  ;; The shortest of `n` runs of `f`, in seconds, and f's last results.
  (var best math.huge)
  (var result nil)
  (for [_ 1 n]
    (collectgarbage)
    (let [t0 (os.clock)
          r (f)]
      (set best (math.min best (- (os.clock) t0)))
      (set result r)))
  (values best result))

(let [(t-enc bytes) (best-of 3 #(assert (wire.encode scene)))
      (t-dec value) (best-of 3 #(assert (wire.decode bytes)))]
  (assert (= (length value.objects) count))
  (assert (= (. value.objects count :radius) (. scene.objects count :radius)))
  (print (string.format "%d spheres: %.1f MB; encode %.3f s, decode %.3f s, total %.3f s (best of 3)"
                        count (/ (length bytes) 1e6) t-enc t-dec (+ t-enc t-dec))))

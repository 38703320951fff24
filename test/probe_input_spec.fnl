;; tier: fast
;; src/app/probe.fnl's reader of `--probe` input: an endless stream is read in
;; chunks and handed out in batches in constant memory, and a long line is refused
;; before it is read whole. Pure: no LÖVE (test/probe_spec.fnl runs the app on both).
(local probe (require :src.app.probe))

(fn endless-file [line]
  "A file that gives `line` over and over, never an end; counts the bytes read."
  (let [block (string.rep line (math.ceil (/ 200000 (length line))))
        f {:bytes 0}]
    (set f.read (fn [self n]
                  (let [off (% self.bytes (length line))]
                    (set self.bytes (+ self.bytes n))
                    (block:sub (+ off 1) (+ off n)))))
    f))

(describe "probe input"
  (fn []
    (it "an endless stream is answered batch by batch in constant memory"
      (fn []
        (let [f (endless-file "0.5 -1 2\n")
              next-batch (probe.point-reader f "stdin")]
          (collectgarbage :collect)
          (var (total growth) (values 0 0))
          (let [base (collectgarbage :count)]
            (for [i 1 64]
              (let [b (assert (next-batch))]
                (assert.is_true (<= (length b) 16384))
                (set total (+ total (length b))))
              ;; What the reader keeps between batches, not garbage not yet swept.
              (when (= 0 (% i 8))
                (collectgarbage :collect)
                (set growth (math.max growth (- (collectgarbage :count) base))))))
          (assert.are.equal (* 64 16384) total)
          (assert.are.same [0.5 -1 2] (. (next-batch) 1))
          (assert.is_true (< growth 1024) (.. "the reader keeps " growth " KB")))))

    (it "a line over 4096 bytes is refused, naming stdin and the line, before it is read whole"
      (fn []
        (let [f (endless-file "1")
              text-head "1 2 3\n\n"
              g {:bytes 0 :read (fn [self n]
                                  (if (= self.bytes 0)
                                      (do (set self.bytes (length text-head)) text-head)
                                      (f:read n)))}
              next-batch (probe.point-reader g "stdin")]
          (assert.are.same [[1 2 3]] (next-batch))
          (let [(points msg) (next-batch)]
            (assert.is_nil points)
            (assert.are.equal "stdin:3: line longer than 4096 bytes; a point is three numbers `x y z`" msg))
          (assert.is_true (< f.bytes (* 1024 1024)) (.. f.bytes " bytes read")))))))

(describe "probe input: numbers that are not finite"
  (fn []
    (it "nan, inf and 1e309 are refused naming the line, after the good lines before them"
      (fn []
        (each [_ bad (ipairs ["nan 0 0" "0 inf 0" "0 0 -inf" "1e309 0 0" "0 0 0x"])]
          (let [text (.. "1 2 3\n" bad "\n4 5 6\n")
                f {:pos 1 :read (fn [self n]
                                  (when (<= self.pos (length text))
                                    (let [s (text:sub self.pos (+ self.pos n -1))]
                                      (set self.pos (+ self.pos n))
                                      s)))}
                next-batch (probe.point-reader f "stdin")]
            (assert.are.same [[1 2 3]] (next-batch) bad)
            (let [(points err) (next-batch)]
              (assert.is_nil points)
              (assert.are.equal (.. "stdin:2: expected three finite numbers `x y z`, got \"" bad "\"")
                                err))))))))

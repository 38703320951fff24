;; tier: fast
;; Progress lines (src/util/status.fnl): rewritten in place and cleared on a terminal,
;; plain lines in a log.
(local status (require :src.util.status))

(fn fake-stream []
  (let [s {:text ""}]
    (fn s.write [self ...] (set self.text (.. self.text (table.concat [...]))))
    (fn s.flush [_])
    s))

(describe "progress lines"
  (fn []
    (it "on a terminal: each update erases the rest of the line, and done! ends it"
      (fn []
        (let [out (fake-stream)
              p (status.new out true)]
          (p.update! "mesh: colours, 12% (7k points), 0.4 s, about 3 s left")
          (p.update! "mesh: colours, 99% (107k points), 1.4 s, under 1 s left")
          (p.update! "mesh: done")
          (p.done!)
          (assert.are.equal (.. "\rmesh: colours, 12% (7k points), 0.4 s, about 3 s left\027[K"
                                "\rmesh: colours, 99% (107k points), 1.4 s, under 1 s left\027[K"
                                "\rmesh: done\027[K\n")
                            out.text)
          ;; What a terminal shows: the last line whole, nothing of the longer ones.
          (let [shown (: (: (out.text:gsub ".*\r" "") :gsub "\027%[K" "") :gsub "\n$" "")]
            (assert.are.equal "mesh: done" shown)))))

    (it "on a terminal: done! with no update writes nothing, and twice ends the line once"
      (fn []
        (let [out (fake-stream)
              p (status.new out true)]
          (p.done!)
          (assert.are.equal "" out.text)
          (p.update! "a")
          (p.done!)
          (p.done!)
          (assert.are.equal "\ra\027[K\n" out.text))))

    (it "in a log: one plain line an update, no control characters"
      (fn []
        (let [out (fake-stream)
              p (status.new out false)]
          (p.update! "frame 1/2")
          (p.update! "frame 2/2")
          (p.done!)
          (assert.are.equal "frame 1/2\nframe 2/2\n" out.text))))

    (it "knows whether stderr is a terminal (a boolean)"
      (fn []
        (assert.are.equal :boolean (type status.terminal?))))))

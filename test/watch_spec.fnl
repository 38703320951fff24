;; tier: fast
;; The file watcher's rules, with a fake file and clock: a version is loaded once the
;; file has not been written for the settle time, judged by its modification time.
(local watch (require :src.app.watch))

(fn info [content mtime ?coarse?]
  {: mtime :coarse? ?coarse? :size (length content) : content})

(fn run [w steps]
  "Feed [time info] pairs; return the non-idle events as [time event]."
  (icollect [_ [t i] (ipairs steps)]
    (let [event (watch.poll! w i t)]
      (when (not= event :idle) [t event]))))

(describe "the scene file watcher"
  (fn []
    (it "loads an edit once the file has not been written for 0.01 s, once"
      (fn []
        (assert.are.equal 0.01 watch.settle-seconds)
        (let [w (watch.new (info "a" 0))]
          (assert.are.same [[10.015 :changed]]
                           (run w [[10 (info "b" 10)] [10.005 (info "b" 10)] [10.015 (info "b" 10)]
                                   [10.025 (info "b" 10)] [10.1 (info "b" 10)] [10.9 (info "b" 10)]])))))

    (it "sees an edit of the same size within the same second (by content)"
      (fn []
        (let [w (watch.new (info "0.5" 10))]
          (assert.are.same [[10.3 :changed]]
                           (run w [[10.3 (info "0.6" 10.05)]])))))

    (it "never loads a file that is still being written, however rarely it looks"
      (fn []
        ;; A writer rewrites the file every 8 ms (truncate, then write: pauses
        ;; shorter than the settle time); the player looks once a second and each
        ;; time sees the half-written text, the same every time. Nothing loads until
        ;; the writing stops.
        (let [w (watch.new (info "old" 0))]
          (assert.are.same [[14.25 :changed]]
                           (run w [[10 (info "{:obj" 9.994)] [11 (info "{:obj" 10.993)]
                                   [12 (info "{:obj" 11.995)] [13 (info "{:obj" 12.992)]
                                   [14 (info "{:objects []}" 14)] [14.25 (info "{:objects []}" 14)]])))))

    (it "with whole-second times, waits until the second after the stamp is over"
      (fn []
        (let [w (watch.new (info "old" 0))]
          (assert.are.same [[11.015 :changed]]
                           (run w [[10.5 (info "new" 10 true)] [11.005 (info "new" 10 true)]
                                   [11.015 (info "new" 10 true)]])))))

    (it "does not report a file briefly missing while an editor renames over it"
      (fn []
        (let [w (watch.new (info "old" 0))]
          (assert.are.same [[10.17 :changed]]
                           (run w [[10 nil] [10.1 nil] [10.155 (info "new" 10.15)] [10.17 (info "new" 10.15)]])))))

    (it "reports a deleted file once, after a second, and a restored one as a change"
      (fn []
        (let [w (watch.new (info "old" 0))]
          (assert.are.same [[11 :deleted] [12.5 :changed]]
                           (run w [[10 nil] [10.5 nil] [11 nil] [11.5 nil] [12 (info "back" 12)]
                                   [12.5 (info "back" 12)]])))))

    (it "reports a file replaced by a directory as unreadable, with the reason"
      (fn []
        (let [w (watch.new (info "old" 0))]
          (assert.are.same [[11 :unreadable]]
                           (run w [[10 {:problem "it is a directory"}] [11 {:problem "it is a directory"}]
                                   [12 {:problem "it is a directory"}]]))
          (assert.are.equal "it is a directory" w.problem))))

    (it "reloads a file that was saved unchanged (touch), and nothing without a save"
      (fn []
        (let [w (watch.new (info "same" 5))]
          (assert.are.same [] (run w [[10 (info "same" 5)] [10.5 (info "same" 5)]]))
          (assert.are.same [[11.5 :changed]] (run w [[11 (info "same" 11)] [11.5 (info "same" 11)]])))))

    (it "lets a failed read stand only when the file stayed the same through it and 0.15 s before"
      (fn []
        ;; The same text, size and time before and after, written long enough ago.
        (assert.is_true (watch.failure-stands? (info "{:obj" 10) (info "{:obj" 10) 10.2))
        ;; Written 50 ms ago: maybe the first half of a write.
        (assert.is_false (watch.failure-stands? (info "{:obj" 10) (info "{:obj" 10) 10.05))
        ;; Written during the read.
        (assert.is_false (watch.failure-stands? (info "{:obj" 10) (info "{:objects []}" 10.3) 10.5))
        (assert.is_false (watch.failure-stands? (info "" 10) (info "{:objects []}" 10) 10.5))
        ;; Missing both times stands; appearing or going meanwhile does not.
        (assert.is_true (watch.failure-stands? nil nil 10))
        (assert.is_false (watch.failure-stands? nil (info "{:obj" 10) 10.5))
        (assert.is_false (watch.failure-stands? (info "{:obj" 10) nil 10.5))
        ;; The same reason it cannot be read, both times, stands.
        (assert.is_true (watch.failure-stands? {:problem "it is a directory"} {:problem "it is a directory"} 10))
        ;; Whole-second times: the second after the stamp must be over too.
        (assert.is_false (watch.failure-stands? (info "{:obj" 10 true) (info "{:obj" 10 true) 10.9))
        (assert.is_true (watch.failure-stands? (info "{:obj" 10 true) (info "{:obj" 10 true) 11.2))))

    (it "after retry!, loads again once the file stayed the same for 0.15 s, even unchanged"
      (fn []
        ;; A scene written in two halves 50 ms apart; a load read the first half at
        ;; 10.02 (it failed, and did not stand): the file is loaded again at the first
        ;; poll the settle time after the second half (10.065, a new version), never
        ;; before, and once.
        (let [first-half (info "{:objects [" 10)
              whole (info "{:objects []}" 10.05)
              w (watch.new (info "old" 0))]
          (watch.loaded! w first-half)
          (assert.is_false (watch.failure-stands? first-half first-half 10.02))
          (watch.retry! w)
          (assert.are.same [[10.065 :changed]]
                           (run w [[10.03 first-half] [10.055 whole] [10.065 whole] [10.11 whole]
                                   [10.3 whole] [10.6 whole]]))
          ;; A retry of a file that did not change after the failed read: loaded
          ;; again all the same, once it is 0.15 s old.
          (watch.loaded! w whole)
          (watch.retry! w)
          (assert.are.same [[10.25 :changed]] (run w [[10.15 whole] [10.25 whole] [10.5 whole]])))))

    (it "reads the file again only when its stat may hide a change"
      (fn []
        (let [st {:kind :file :mtime 10 :size 5 :ino 7 :dev 1}
              read {:mtime 10 :size 5 :ino 7 :dev 1 :read-at 10.5}
              with (fn [t k v] (doto (collect [key value (pairs t)] key value) (tset k v)))]
          (assert.is_false (watch.read-again? read st))
          ;; Nothing read yet, the file missing, or not a file.
          (assert.is_true (watch.read-again? nil st))
          (assert.is_true (watch.read-again? read nil))
          (assert.is_true (watch.read-again? read (with st :kind :directory)))
          ;; A new time, size, inode (renamed over) or device.
          (assert.is_true (watch.read-again? read (with st :mtime 10.001)))
          (assert.is_true (watch.read-again? read (with st :size 6)))
          (assert.is_true (watch.read-again? read (with st :ino 8)))
          (assert.is_true (watch.read-again? read (with st :dev 2)))
          ;; Read within a clock tick of its time: a second write may share it.
          (assert.is_true (watch.read-again? (with read :read-at 10.01) st))
          ;; Whole-second times say too little.
          (assert.is_true (watch.read-again? read (with st :coarse? true))))))

    (it "starts afresh after loaded!"
      (fn []
        (let [w (watch.new (info "a" 0))]
          (run w [[10 (info "b" 10)]])
          (watch.loaded! w (info "b" 10))
          (assert.are.same [] (run w [[10.5 (info "b" 10)] [11 (info "b" 10)]])))))))

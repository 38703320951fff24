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
    (it "loads an edit once the file has not been written for 0.2 s, once"
      (fn []
        (let [w (watch.new (info "a" 0))]
          (assert.are.same [[10.3 :changed]]
                           (run w [[10 (info "b" 10)] [10.1 (info "b" 10)] [10.3 (info "b" 10)]
                                   [10.5 (info "b" 10)] [10.9 (info "b" 10)]])))))

    (it "sees an edit of the same size within the same second (by content)"
      (fn []
        (let [w (watch.new (info "0.5" 10))]
          (assert.are.same [[10.3 :changed]]
                           (run w [[10.3 (info "0.6" 10.05)]])))))

    (it "never loads a file that is still being written, however rarely it looks"
      (fn []
        ;; A writer rewrites the file every 50 ms (truncate, then write); the player
        ;; looks once a second and each time sees the half-written text, the same
        ;; every time. Nothing loads until the writing stops.
        (let [w (watch.new (info "old" 0))]
          (assert.are.same [[14.25 :changed]]
                           (run w [[10 (info "{:obj" 9.98)] [11 (info "{:obj" 10.97)]
                                   [12 (info "{:obj" 11.99)] [13 (info "{:obj" 12.96)]
                                   [14 (info "{:objects []}" 14)] [14.25 (info "{:objects []}" 14)]])))))

    (it "with whole-second times, waits until the second after the stamp is over"
      (fn []
        (let [w (watch.new (info "old" 0))]
          (assert.are.same [[11.3 :changed]]
                           (run w [[10.5 (info "new" 10 true)] [11.1 (info "new" 10 true)]
                                   [11.3 (info "new" 10 true)]])))))

    (it "does not report a file briefly missing while an editor renames over it"
      (fn []
        (let [w (watch.new (info "old" 0))]
          (assert.are.same [[10.5 :changed]]
                           (run w [[10 nil] [10.1 nil] [10.2 (info "new" 10.15)] [10.5 (info "new" 10.15)]])))))

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

    (it "starts afresh after loaded!"
      (fn []
        (let [w (watch.new (info "a" 0))]
          (run w [[10 (info "b" 10)]])
          (watch.loaded! w (info "b" 10))
          (assert.are.same [] (run w [[10.5 (info "b" 10)] [11 (info "b" 10)]])))))))

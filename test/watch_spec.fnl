;; The file watcher's settling rules, with a fake file and clock.
(local watch (require :src.watch))

(fn info [content ?mtime]
  {:mtime (or ?mtime 100) :size (length content) :content content})

(fn run [w steps]
  "Feed [time info] pairs; return the non-idle events as [time event]."
  (icollect [_ [t i] (ipairs steps)]
    (let [event (watch.poll! w i t)]
      (when (not= event :idle) [t event]))))

(describe "the scene file watcher"
  (fn []
    (it "reports an edit once it has settled, once"
      (fn []
        (let [w (watch.new (info "a"))]
          (assert.are.same [[0.3 :changed]]
                           (run w [[0 (info "b" 101)] [0.1 (info "b" 101)] [0.3 (info "b" 101)]
                                   [0.5 (info "b" 101)] [0.9 (info "b" 101)]])))))

    (it "sees an edit within the same second of the same size (by content)"
      (fn []
        (let [w (watch.new (info "0.5"))]
          (assert.are.same [[0.3 :changed]]
                           (run w [[0 (info "0.6")] [0.3 (info "0.6")]])))))

    (it "waits while an editor truncates and then writes"
      (fn []
        (let [w (watch.new (info "old"))]
          ;; Empty for a moment, then half written, then complete: one change, at the end.
          (assert.are.same [[0.6 :changed]]
                           (run w [[0 (info "")] [0.1 (info "{:obj")] [0.2 (info "{:objects []}")]
                                   [0.3 (info "{:objects []}")] [0.6 (info "{:objects []}")]])))))

    (it "does not report a file briefly missing while an editor renames over it"
      (fn []
        (let [w (watch.new (info "old"))]
          (assert.are.same [[0.5 :changed]]
                           (run w [[0 nil] [0.1 nil] [0.2 (info "new")] [0.5 (info "new")]])))))

    (it "reports a deleted file once, after a second, and a restored one as a change"
      (fn []
        (let [w (watch.new (info "old"))]
          (assert.are.same [[1 :deleted] [2.5 :changed]]
                           (run w [[0 nil] [0.5 nil] [1 nil] [1.5 nil] [2 (info "back")]
                                   [2.5 (info "back")]])))))

    (it "reloads a file that was saved unchanged (touch), and nothing without a save"
      (fn []
        (let [w (watch.new (info "same"))]
          (assert.are.same [] (run w [[0 (info "same")] [0.5 (info "same")]]))
          (assert.are.same [[1.5 :changed]] (run w [[1 (info "same" 200)] [1.5 (info "same" 200)]])))))

    (it "starts afresh after loaded!"
      (fn []
        (let [w (watch.new (info "a"))]
          (run w [[0 (info "b")]])
          (watch.loaded! w (info "b"))
          (assert.are.same [] (run w [[0.5 (info "b")] [1 (info "b")]])))))))

;; tier: fast
;; The mesher on every core (issue 46): the leaves in shares, each share taken by a
;; forked process through corners to projection, the results merged
;; (src/mesh/contour.fnl's mesh-shares!, src/util/fork.fnl's run-shares). The mesh
;; must be the one a single process makes, byte for byte, however the leaves are
;; cut: a face whose decision needs the cell across a share's border is decided
;; alike by both shares, or the share is taken again with the one across.

(local load (require :src.scene.load))
(local contour (require :src.mesh.contour))
(local mesh-scene (require :src.mesh.scene))
(local fork (require :src.util.fork))

(fn mesher [path resolution]
  "A function (fn [workers share-leaves]) meshing the scene at `path`."
  (let [selection (assert (mesh-scene.select-objects (assert (load.load-file path))))
        field (assert (mesh-scene.cpu-field selection.scene))]
    (fn [workers share-leaves]
      (contour.mesh field (doto (mesh-scene.grid-for selection resolution)
                            (tset :workers workers)
                            (tset :share-leaves share-leaves))))))

(fn assert-same [one other what]
  ;; Every number as written in full (%.17g): equal lists, not nearly equal.
  (let [text (fn [list] (table.concat (icollect [_ v (ipairs list)] (string.format "%.17g" v)) " "))]
    (assert.are.equal (length one.positions) (length other.positions) what)
    (assert.is_true (= (text one.positions) (text other.positions)) (.. what ": positions differ"))
    (assert.is_true (= (text one.triangles) (text other.triangles)) (.. what ": triangles differ"))
    (assert.are.equal one.stats.flipped other.stats.flipped what)
    (assert.are.equal one.stats.crossings other.stats.crossings what)))

(describe "the mesher's shares"
  (fn []
    (it "make the mesh one process makes, cut in 2 to 16 shares (custom: faces decided across borders)"
      (fn []
        (let [mesh (mesher "scenes/custom.fnl" 48)
              one (mesh 1)]
          (assert.are.equal 1 one.stats.shares)
          ;; custom's thin walls have ambiguous faces joined on both sides (20
          ;; reversed at 48 cells), some on the shares' borders.
          (assert.is_true (< 0 one.stats.flipped))
          (each [_ [workers leaves] (ipairs [[2 16] [8 8] [16 8]])]
            (let [m (mesh workers leaves)
                  what (string.format "%d workers, shares of %d leaves" workers leaves)]
              (assert.is_true (< 1 m.stats.shares) what)
              ;; Decided by both shares, none taken again (an undecided face
              ;; would be taken again, and still give the same mesh).
              (assert.are.equal 0 m.stats.retaken what)
              (assert-same one m what))))))
    (it "take a share again with the one across where a face cannot be decided alone (flower)"
      (fn []
        (let [mesh (mesher "scenes/flower.fnl" 64)
              one (mesh 1)
              m (mesh 8 8)]
          ;; Cut in 8, a petal's joined faces meet a border where the cells
          ;; have more than that face joined: the share is taken again.
          (assert.is_true (< 0 m.stats.retaken) "no share taken again")
          (assert-same one m "8 shares"))))
    (it "are not used for a field that cannot run in a child, or for one worker"
      (fn []
        (let [selection (assert (mesh-scene.select-objects
                                  (assert (load.load-file "scenes/organic.fnl"))))
              field (assert (mesh-scene.cpu-field selection.scene))
              grid (mesh-scene.grid-for selection 48)
              ;; The same field without its :fork-safe? (a GPU field has none).
              plain (collect [k v (pairs field)] (when (not= k :fork-safe?) (values k v)))]
          (tset grid :share-leaves 8)
          (assert.are.equal 1 (. (contour.mesh plain grid) :stats :shares))
          (tset grid :workers 1)
          (assert.are.equal 1 (. (contour.mesh field grid) :stats :shares)))))))

(describe "settling the runs of shares (contour.settle-runs)"
  (fn []
    ;; A result is {:meets [a b]} (the shares it would have to be taken with) or
    ;; {}; taking lo to hi again gives what `again` says for that range.
    (fn settle [met-by again]
      (let [runs (fcollect [s 1 (length met-by)] [s s {:meets (. met-by s)}])
            taken []
            met (fn [r] (case r.meets [a b] (values a b) _ (values 0 0)))
            take (fn [lo hi]
                   (table.insert taken [lo hi])
                   {:meets (. again (.. lo "-" hi))})]
        (values (icollect [_ [lo hi] (ipairs (contour.settle-runs runs met take))] [lo hi])
                taken)))
    (it "keeps runs that meet none"
      (fn []
        (let [(runs taken) (settle [false false false] {})]
          (assert.are.same [[1 1] [2 2] [3 3]] runs)
          (assert.are.same [] taken))))
    (it "takes a run again with the ones up to the one it met"
      (fn []
        (let [(runs taken) (settle [false [4 4] false false false] {})]
          (assert.are.same [[1 1] [2 4] [5 5]] runs)
          (assert.are.same [[2 4]] taken))))
    (it "covers a run already taken again whole when a later one meets part of it"
      (fn []
        ;; 5 meets 6 (taken again as 5-6), then 7 meets 6: the new run must
        ;; cover 5 to 7, not 6 to 7 (share 5 would be lost).
        (let [(runs taken) (settle [false false false false [6 6] false [6 6]] {})]
          (assert.are.same [[1 1] [2 2] [3 3] [4 4] [5 7]] runs)
          (assert.are.same [[5 6] [5 7]] taken))))
    (it "widens a run taken again that still meets another"
      (fn []
        (let [(runs taken) (settle [[2 2] false false false] {"1-2" [4 4]})]
          (assert.are.same [[1 4]] runs)
          (assert.are.same [[1 2] [1 4]] taken))))))

(describe "fork.run-shares"
  (fn []
    (fn numbers [s ?out ?room]
      ;; Share s's numbers: s and then s + k / 7 for k up to 10 s, in ?out where
      ;; they fit (as run-shares asks).
      (let [n (+ 1 (* 10 s))
            list (if (and ?out (<= n ?room)) ?out [])]
        (tset list 1 s)
        (for [k 2 n] (tset list k (+ s (/ k 7))))
        (values list n)))
    (fn as-table [[list n]]
      (fcollect [k 1 n] (. list k)))
    (it "gives every share's numbers, in order, however many processes take them"
      (fn []
        (let [got (fork.run-shares 5 100 (fn [s ?out ?room] (numbers s ?out ?room))
                                   (fn [results] (icollect [_ r (ipairs results)] (as-table r))))]
          (assert.are.equal 5 (length got))
          (each [s list (ipairs got)]
            (assert.are.same (as-table [(numbers s)]) list (.. "share " s))))))
    (it "runs here a share a child failed at, or whose numbers did not fit"
      (fn []
        (let [got (fork.run-shares
                    4 25
                    (fn [s ?out ?room]
                      ;; Share 2 fails in a child; shares 3 and 4 (31 and 41
                      ;; numbers) do not fit in 25.
                      (when (and (= s 2) (fork.child?)) (error "share 2 cannot run in a child"))
                      (numbers s ?out ?room))
                    (fn [results] (icollect [_ r (ipairs results)] (as-table r))))]
          (each [s list (ipairs got)]
            (assert.are.same (as-table [(numbers s)]) list (.. "share " s))))))
    (it "stops the children when this process's share fails (a stop asked for)"
      (fn []
        ;; Share 2, in a child, works for 10 s of its CPU time and then writes a
        ;; file; share 1, here, fails at once. The child must be stopped, not
        ;; waited for: no file.
        (let [marker (os.tmpname)]
          (os.remove marker)
          (let [(ok? err) (pcall fork.run-shares 2 10
                                 (fn [s ?out ?room]
                                   (if (= s 1) (error "stopped here")
                                       (let [t0 (os.clock)]
                                         (while (< (- (os.clock) t0) 10) nil)
                                         (with-open [f (io.open marker :w)] (f:write "done"))
                                         (numbers s ?out ?room))))
                                 (fn [results] results))]
            (assert.is_false ok?)
            (assert.truthy (string.find (tostring err) "stopped here" 1 true))
            (let [f (io.open marker)]
              (when f (f:close) (os.remove marker))
              (assert.is_nil f "the child went on to the end"))))))
    (it "lets a child collect its heap only when asked to (?collect?)"
      (fn []
        ;; Each share's one number: 1 where its process may collect (see
        ;; fork.collects?). This process always may; a child only with ?collect?.
        ;; Share 2 must be a child's: this process, at share 1, waits until a
        ;; child has begun share 2 (it says so in a file), so it cannot take that
        ;; share itself (a wait for an event, not a verdict on time: at most
        ;; 60 s, and only where fork() is there).
        (let [linux? (= "Linux" (. (require :ffi) :os))]
          (each [_ [collect? expected] (ipairs [[false 0] [true 1]])]
            (let [marker (os.tmpname)
                  _ (os.remove marker)
                  started? #(case (io.open marker) f (do (f:close) true) _ false)
                  got (fork.run-shares
                        2 4
                        (fn [s ?out]
                          (if (and (= s 2) (fork.child?))
                              (with-open [f (io.open marker :w)] (f:write "2"))
                              (and (= s 1) linux?)
                              (let [t0 (os.time)]
                                (while (and (not (started?)) (< (- (os.time) t0) 60)) nil)))
                          (let [list (or ?out [])]
                            (tset list 1 (if (fork.collects?) 1 0))
                            (values list 1)))
                        (fn [results] (icollect [_ [list] (ipairs results)] (. list 1)))
                        collect?)]
              (os.remove marker)
              (assert.are.equal 1 (. got 1) "this process")
              (when linux?
                (assert.are.equal expected (. got 2)
                                  (.. "a child, ?collect? " (tostring collect?)))))))))
    (it "raises the error of a share that fails here too"
      (fn []
        (let [(ok? err) (pcall fork.run-shares 3 10
                               (fn [s ?out ?room]
                                 (when (= s 3) (error "share 3 cannot run"))
                                 (numbers s ?out ?room))
                               (fn [results] results))]
          (assert.is_false ok?)
          (assert.truthy (string.find (tostring err) "share 3 cannot run" 1 true)))))))

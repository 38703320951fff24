;; tier: fast
;; Work shared among processes (src/util/fork.fnl): children made by fork() compute
;; shares of a range into shared memory; the list is the one a single process makes,
;; a child that fails has its share computed again here, and a mesh's field gives
;; the same numbers split or not.

(local fork (require :src.util.fork))
(local load (require :src.scene.load))
(local mesh-scene (require :src.mesh.scene))

(fn children []
  "This process's children, as a sorted list of process ids, from Linux's
/proc/PID/task/PID/children (read here: a shell would be a child itself); nil
where that is not there."
  (let [libc (require :src.util.libc)
        native (libc.declare [:getpid])]
    (when native
      (let [pid (native.getpid)]
        (case (io.open (string.format "/proc/%d/task/%d/children" pid pid))
          f (let [text (with-open [f f] (f:read :*a))
                  pids (icollect [w (text:gmatch "%d+")] (tonumber w))]
              (table.sort pids)
              pids))))))

(fn compute [first last out]
  ;; Item i's two numbers: a value with all its bits (not a small integer), and i.
  (for [i first last]
    (tset out (- (* 2 i) 1) (math.sin (* i 0.001)))
    (tset out (* 2 i) i)))

(describe "work shared among processes"
  (fn []
    (it "gives the list one process gives, whatever the workers"
      (fn []
        (let [n (* 3 fork.min-share)
              (alone) (fork.split-range n 2 compute 1)]
          (assert.are.equal (* 2 n) (length alone))
          (each [_ workers (ipairs [2 3])]
            (let [(shared own) (fork.split-range n 2 compute workers)]
              ;; This process computed a share only: the others came back from
              ;; the children (where fork() is there: Linux).
              (when (= "Linux" (. (require :ffi) :os))
                (assert.is_true (< own n) (.. "own share " own)))
              (assert.are.same alone shared (.. workers " workers")))))))
    (it "computes a failed child's share itself, and its error is raised here"
      (fn []
        ;; The items of the second half fail in a child and again here.
        (let [n (* 2 fork.min-share)
              failing (fn [first last out]
                        (for [i first last]
                          (when (> i fork.min-share) (error (.. "item " i " cannot be computed")))
                          (tset out i i)))
              (ok? err) (pcall fork.split-range n 1 failing 2)]
          (assert.is_false ok?)
          (assert.truthy (string.find (tostring err) "cannot be computed" 1 true)))))
    (it "waits for its children when this process's own share fails"
      (fn []
        ;; The first half (this process's) fails; the child computing the second
        ;; half is waited for before the error goes up: none is left behind.
        (let [n (* 2 fork.min-share)
              failing (fn [first last out]
                        (for [i first last]
                          (when (<= i fork.min-share) (error "the first half cannot be computed"))
                          (tset out i i)))
              before (children)
              (ok? err) (pcall fork.split-range n 1 failing 2)]
          (assert.is_false ok?)
          (assert.truthy (string.find (tostring err) "first half cannot" 1 true))
          ;; Where Linux lists a process's children: none that was not there
          ;; before the call (another spec's scene worker may be one of them).
          (when before
            (let [known (collect [_ pid (ipairs before)] pid true)]
              (each [_ pid (ipairs (children))]
                (assert.is_true (. known pid) (.. "a child left behind: " pid))))))))
    (it "makes a mesh's field give the same distances and colours split or not"
      (fn []
        (let [scene (. (mesh-scene.select-objects (assert (load.load-file "scenes/organic.fnl"))) :scene)
              one (assert (mesh-scene.cpu-field scene 1))
              two (assert (mesh-scene.cpu-field scene 2))
              n (* 2 fork.min-share)
              flat (fcollect [k 1 (* 3 n)] (- (* 6 (math.sin (* k 0.37))) 1))]
          ;; The first call of each runs in one process and measures; organic's
          ;; field costs microseconds a point, so later batches are split where
          ;; the forks are worth it. The numbers are the same either way.
          (for [_ 1 3]
            (assert.are.same (one.distances flat n) (two.distances flat n))
            (assert.are.same (one.colors flat n) (two.colors flat n))))))))

;; Work on every core: a range of items split between this process and children made
;; by fork(), each child writing its share's numbers into memory shared with the
;; parent (an anonymous shared mapping) and leaving with _exit. A child starts as a
;; copy of the parent (copy-on-write), so it has the same functions and data and
;; needs nothing sent to it; it makes no garbage collection (the collector is
;; stopped: a finalizer could reach a resource the parent still uses) and no output.
;; A share whose child failed is computed again by the parent, whose error, if it
;; fails too, says why. Linux through LuaJIT's FFI; elsewhere, or with one core, the
;; parent computes everything.

(local libc (require :src.util.libc))
;; `pairs` under another name (LuaJIT's ITERN: see src/util/wire.fnl).
(local each-pair pairs)
(local ffi libc.ffi)

(local native
  (when (and ffi (= ffi.os :Linux))
    (libc.declare [:fork :_exit :mmap :munmap :waitpid :sysconf :nanosleep])))

(local table-new (let [(ok? new) (pcall require :table.new)]
                   (if ok? (fn [n] (new n 0)) (fn [] []))))

(local filestat (require :src.util.filestat))
(local clock filestat.monotonic)

;; sysconf's _SC_NPROCESSORS_ONLN on Linux; mmap's PROT_READ | PROT_WRITE and
;; MAP_SHARED | MAP_ANONYMOUS.
(local online-processors 84)
(local read-write 3)
(local shared-anonymous 0x21)

;; Fewer items than this are not split: a fork of a large heap costs milliseconds
;; (its page tables are copied), more than a few thousand field values.
(local min-share 4096)

;; Whether this process is a child made here: it splits nothing further.
(var child? false)

(fn cores []
  "The processors online (1 where that is unknown)."
  (if native (math.max 1 (tonumber (native.sysconf online-processors))) 1))

(fn exited-cleanly? [pid]
  (let [status (ffi.new "int[1]")]
    (and (= pid (native.waitpid pid status 0))
         ;; WIFEXITED and WEXITSTATUS 0: the low 16 bits all zero.
         (= 0 (% (. status 0) 65536)))))

(fn split-range [n width compute workers]
  "As a splitter's function (see splitter), the range always shared among `workers`
processes when it has min-share items for each (1: none forked). Returns the list,
and the items this process computed and their seconds."
  (let [out (table-new (* n width))
        workers (if child? 1 (math.min workers (math.floor (/ n min-share))))]
    (if (or (not native) (< workers 2))
        (let [t0 (clock)]
          (compute 1 n out)
          (values out n (- (clock) t0)))
        (let [share (math.ceil (/ n workers))
              bytes (* n width 8)
              mem (native.mmap nil bytes read-write shared-anonymous -1 0)
              failed? (= (ffi.cast "intptr_t" mem) -1)
              shared (ffi.cast "double *" mem)
              children []]
          (when (not failed?)
            (for [w 2 workers]
              (let [first (+ 1 (* (- w 1) share))
                    last (math.min n (* w share))
                    pid (native.fork)]
                (if (= pid 0)
                    (do (collectgarbage :stop)
                        (set child? true)
                        (let [ok? (pcall (fn []
                                           (let [mine []]
                                             (compute first last mine)
                                             (for [q (+ 1 (* (- first 1) width)) (* last width)]
                                               (tset shared (- q 1) (. mine q))))))]
                          (native._exit (if ok? 0 1))))
                    (< pid 0) nil
                    (table.insert children {: pid : first : last})))))
          ;; This process's share, and any share no child took. An error here
          ;; waits for the children and frees the mapping before it goes on up
          ;; (no process or memory left behind in a player that goes on).
          (local t0 (clock))
          (local (own-ok? own-err)
            (pcall (fn []
                     (compute 1 (math.min n share) out)
                     (let [taken {}]
                       (each [_ c (ipairs children)] (tset taken c.first true))
                       (for [w 2 workers]
                         (let [first (+ 1 (* (- w 1) share))]
                           (when (not (. taken first))
                             (compute first (math.min n (* w share)) out))))))))
          (local own-seconds (- (clock) t0))
          (local clean (icollect [_ c (ipairs children)] (exited-cleanly? c.pid)))
          (when own-ok?
            (each [i {: first : last} (ipairs children)]
              (if (. clean i)
                  (for [q (+ 1 (* (- first 1) width)) (* last width)]
                    (tset out q (. shared (- q 1))))
                  (compute first last out))))
          (when (not failed?) (native.munmap mem bytes))
          (when (not own-ok?) (error own-err 0))
          (values out (math.min n share) own-seconds)))))

(local shared-anonymous-unreserved 0x4021)
;; waitpid's WNOHANG.
(local no-hang 1)

(fn wait-for [pid done]
  "Waits for child `pid` to say it is done (done[0] set) or to leave: true when it
said so (it may still be leaving: see reap)."
  (let [status (ffi.new "int[1]")
        pause (ffi.new "rm_timespec_t" {:sec 0 :nsec 50000})]
    (var (said? left?) (values false false))
    (while (not (or said? left?))
      (if (not= 0 (. done 0)) (set said? true)
          (= pid (native.waitpid pid status no-hang)) (set left? true)
          (native.nanosleep pause nil)))
    ;; A child that left may have said so just before.
    (or said? (not= 0 (. done 0)))))

(fn run-shares [shares room run use]
  "Runs (run s out room) for s from 1 to `shares`: share 1 in this process, the
others each in a child made by fork(), at once. `run` writes share s's numbers at
out[1..n] (`out` an FFI double array with `room` places from 1, in memory shared
with the children) and returns out and n; where they do not fit, it returns another
list (a table or FFI array from 1) and n instead. Calls (use results), results
being per share [numbers n] (the numbers read in place, from index 1), and returns
what it returns, having freed the shared memory. A share whose child failed, or
whose numbers did not fit, is run here again, so an error it raises is this
process's; with no fork() (or in a child) every share runs here. The children are
waited for only until they say they are done, and reaped after `use`: a child's
leaving (freeing its memory) takes milliseconds."
  (let [region (+ room 2)
        bytes (* shares region 8)
        mem (when (and native (not child?) (< 1 shares))
              (native.mmap nil bytes read-write shared-anonymous-unreserved -1 0))
        mapped? (and mem (not= (ffi.cast "intptr_t" mem) -1))
        base (when mapped? (ffi.cast "double *" mem))
        ;; Share s's region: its done word at [0] (n + 1 once written), numbers from 1.
        region-of (fn [s] (+ base (* (- s 1) region)))
        children []
        results []]
    (when mapped?
      (for [s 2 shares]
        (let [pid (native.fork)]
          (if (= pid 0)
              (do (collectgarbage :stop)
                  (set child? true)
                  (let [out (region-of s)
                        (ok? list n) (pcall run s out room)]
                    (when (and ok? (= list out))
                      (tset out 0 (+ n 1)))
                    (native._exit (if (and ok? (= list out)) 0 1))))
              (< pid 0) nil
              (tset children s pid)))))
    ;; This process's share (and the others', without children); the children are
    ;; waited for even when it fails (none left behind in a player that goes on).
    (local (ok? err)
      (pcall (fn []
               (for [s 1 shares]
                 (when (not (. children s))
                   (let [(list n) (if mapped? (run s (region-of s) room) (run s))]
                     (tset results s [list n])))))))
    (for [s 2 shares]
      (case (. children s)
        pid (let [done (region-of s)]
              (when (wait-for pid done)
                (tset results s [done (- (. done 0) 1)])))))
    (local (used-ok? value)
      (pcall (fn []
               (when (not ok?) (error err 0))
               (for [s 2 shares]
                 (when (not (. results s))
                   (let [(list n) (run s)]
                     (tset results s [list n]))))
               (use results))))
    (each [_ pid (each-pair children)] (exited-cleanly? pid))
    (when mapped? (native.munmap mem bytes))
    (when (not used-ok?) (error value 0))
    value))

(fn fork-cost []
  ;; Seconds a fork costs the parent, from the heap's size (measured: 1 ms, and
  ;; 0.05 to 0.07 ms a MB, copying page tables and then the pages it writes to).
  (+ 0.001 (* 7e-5 (/ (collectgarbage :count) 1024))))

(fn splitter [?workers]
  "A function (fn [n width compute]) -> item i's `width` numbers, for i from 1 to
n, in one flat list (item i's k-th at (i - 1) * width + k), `compute` (fn [first
last out]) writing those of items first to last into the table `out` at those
places. The range is shared among ?workers processes (default: the cores) when
the work is worth the forks: the time an item took in the calls before (the
first call runs here alone; each measures this process's share) times n, against
one and a half times what the forks cost (see fork-cost). The list is the same
either way."
  (let [workers (or ?workers (cores))
        seen {:items 0 :seconds 0}]
    (fn [n width compute]
      (let [per-item (when (< 0 seen.items) (/ seen.seconds seen.items))
            split? (and per-item (< 1 workers)
                        (> (* per-item n (/ (- workers 1) workers)) (* 1.5 workers (fork-cost))))
            (out items seconds) (split-range n width compute (if split? workers 1))]
        (set seen.items (+ seen.items items))
        (set seen.seconds (+ seen.seconds seconds))
        out))))

{: splitter : split-range : run-shares : cores : min-share
 :child? (fn [] child?)}

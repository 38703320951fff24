;; Work on every core: a range of items split between this process and children made
;; by fork() (split-range, splitter), or shares of a job taken by one process a core
;; from a queue (run-shares: the mesher's leaves), each child writing its numbers
;; into memory shared with the parent (an anonymous shared mapping) and leaving
;; with _exit. A child starts as a copy of the parent (copy-on-write), so it has the
;; same functions and data and needs nothing sent to it; it makes no garbage
;; collection (the collector is stopped: a finalizer could reach a resource the
;; parent still uses; but see run-shares' ?collect?), no output, and splits nothing
;; further. A share whose child
;; failed is computed again by the parent, whose error, if it fails too, says why.
;; Linux through LuaJIT's FFI; elsewhere, or with one core, the parent computes
;; everything.

(local libc (require :src.util.libc))
;; `pairs` under another name (LuaJIT's ITERN: see src/util/wire.fnl).
(local each-pair pairs)
(local ffi libc.ffi)

(local native
  (when (and ffi (= ffi.os :Linux))
    (libc.declare [:fork :_exit :mmap :munmap :waitpid :sysconf :nanosleep :pipe :read
                   :write :close :kill])))

(local {: table-new} (require :src.util.arrays))

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

;; Whether this process is a child made here, or has children working at shares
;; (run-shares): then it splits nothing further (every core is busy). A child whose
;; parent collected its heap just before the fork may collect its own (see
;; run-shares).
(var child? false)
(var sharing? false)
(var child-collects? false)

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
        workers (if (or child? sharing?) 1 (math.min workers (math.floor (/ n min-share))))]
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
;; waitpid's WNOHANG; SIGKILL.
(local no-hang 1)
(local sigkill 9)

(fn pause! []
  (native.nanosleep (ffi.new "rm_timespec_t" {:sec 0 :nsec 50000}) nil))

(fn ticket-queue [shares first]
  "A pipe holding the numbers `first` to `shares` (4 bytes each), its writing end closed:
processes made after take the shares from it one at a time (a pipe's read of 4
bytes is whole, so no two take one), and read nothing once they are gone. Returns
its reading end, or nil (no pipe)."
  (let [fds (ffi.new "int[2]")]
    (when (= 0 (native.pipe fds))
      (let [ticket (ffi.new "int32_t[1]")]
        (for [s first shares]
          (tset ticket 0 s)
          (native.write (. fds 1) ticket 4))
        (native.close (. fds 1))
        (. fds 0)))))

(fn take-ticket [fd]
  "The next share from a ticket-queue, or nil when none is left."
  (let [ticket (ffi.new "int32_t[1]")]
    (when (= 4 (native.read fd ticket 4)) (. ticket 0))))

(fn run-shares [shares room run use ?collect? ?waiting]
  "Runs (run s out room) for every share s from 1 to `shares`, in this process and
in children made by fork() (one per core, at most one per share): share 1 here,
each process then taking the next share left as it gets free (so a share that
takes longer holds up no other). `run` writes share s's numbers at out[1..n]
(`out` an FFI double array with `room` places from 1, in memory shared by the
processes) and returns out and n; where they do not fit, it returns another list
(a table or FFI array from 1) and n instead. Called as (run s), in this process,
what it returns is passed on as it is. Calls (use results), results being per
share [numbers n] (the numbers read in place, from index 1) or what (run s)
returned, and returns what it returns, having freed the shared memory.

A share a child did not finish (it failed, or its numbers did not fit) is run here
again, so an error it raises is this process's; with no fork() (or in a child)
every share runs here. Where this process's share fails (a stop asked for, an
error), or ?waiting raises (called about every 10 ms while this process waits for
the children), the children are killed and reaped and the error goes up.
Otherwise they are reaped after `use`: a child's leaving (freeing its memory)
takes milliseconds.

With ?collect? this process collects its heap before the forks, and the children
keep their collectors: no object a finalizer could act on is garbage in them then
(none was at the fork, and a share lets go of none of its parent's), so their
garbage is freed as it goes instead of kept to the end (a share of a mesh at 512
cells held twice its parent's memory). It costs a full collection of this heap."
  (let [region (+ room 2)
        bytes (* shares region 8)
        workers (math.min (cores) shares)
        mem (when (and native (not child?) (< 1 workers))
              (native.mmap nil bytes read-write shared-anonymous-unreserved -1 0))
        mapped? (and mem (not= (ffi.cast "intptr_t" mem) -1))
        base (when mapped? (ffi.cast "double *" mem))
        ;; Share 1 is this process's; the children take the others from here.
        queue (when mapped? (ticket-queue shares 2))
        ;; Share s's region: its done word at [0] (n + 1 once written), numbers from 1.
        region-of (fn [s] (+ base (* (- s 1) region)))
        children []
        results []]
    (when (and queue ?collect?) (collectgarbage))
    (when queue
      (for [_ 2 workers]
        (let [pid (native.fork)]
          (if (= pid 0)
              (do (when (not ?collect?) (collectgarbage :stop))
                  (set (child? child-collects?) (values true (= true ?collect?)))
                  (var ok? true)
                  (var s (take-ticket queue))
                  (while (and ok? s)
                    (let [out (region-of s)
                          (run-ok? list n) (pcall run s out room)]
                      (if (and run-ok? (= list out))
                          (tset out 0 (+ n 1))
                          (set ok? false)))
                    ;; (A child that failed takes no more: the others, or this
                    ;; process afterwards, take what is left.)
                    (set s (when ok? (take-ticket queue))))
                  (native._exit (if ok? 0 1)))
              (< 0 pid) (table.insert children pid)))))
    ;; This process's shares, then any a child did not finish; the children are
    ;; waited for even when one fails (none left behind in a player that goes on).
    (set sharing? (< 0 (length children)))
    (local (ok? err)
      (pcall (fn []
               (when queue
                 (let [(list n) (run 1)]
                   (tset results 1 [list n]))
                 (var s (take-ticket queue))
                 (while s
                   (let [(list n) (run s (region-of s) room)]
                     (tset results s [list n]))
                   (set s (take-ticket queue)))))))
    (set sharing? false)
    (when queue (native.close queue))
    ;; This process failed (or was asked to stop): the children's work is not
    ;; wanted, and a stop must not wait for it.
    (when (not ok?)
      (each [_ pid (ipairs children)] (native.kill pid sigkill)))
    ;; Until every share is done or every child has left (or ?waiting raises).
    (local (waited-ok? wait-err)
      (pcall (fn []
               (let [status (ffi.new "int[1]")
                     running (collect [_ pid (ipairs children)] pid true)
                     done? (fn [s] (or (. results s) (and mapped? (not= 0 (. (region-of s) 0)))))]
                 (var rounds 0)
                 (while (and (next running)
                             (not (faccumulate [all? true s 1 shares] (and all? (done? s)))))
                   (each [pid (each-pair (collect [p (each-pair running)] p true))]
                     (when (= pid (native.waitpid pid status no-hang))
                       (tset running pid nil)))
                   (set rounds (+ rounds 1))
                   (when (and ok? ?waiting (= 0 (% rounds 200))) (?waiting))
                   (pause!))))))
    (when (not waited-ok?)
      (each [_ pid (ipairs children)] (native.kill pid sigkill)))
    (local (used-ok? value)
      (pcall (fn []
               (when (not ok?) (error err 0))
               (when (not waited-ok?) (error wait-err 0))
               (for [s 1 shares]
                 (when (not (. results s))
                   (let [done (when mapped? (. (region-of s) 0))]
                     (tset results s (if (and done (not= 0 done))
                                         [(region-of s) (- done 1)]
                                         (let [(list n) (run s)] [list n]))))))
               (use results))))
    (each [_ pid (ipairs children)] (exited-cleanly? pid))
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
 :child? (fn [] child?)
 :collects? (fn [] (or (not child?) child-collects?))}

;; tier: fast
;; The worker's seccomp filter (src/util/confine.fnl) run by a small classic-BPF
;; interpreter on made-up system calls: what it allows, refuses and kills, without
;; installing it. (test/worker_spec.fnl makes the real calls from a confined process.)
(local confine (require :src.util.confine))

(local audit-arch-x64 0xc000003e)
(local verdicts {0x7fff0000 :allow 0x80000000 :kill 0x00050001 :eperm})

(fn word [data offset]
  ;; The 32-bit word of seccomp_data at `offset`: nr 0, arch 4, args[i] at 16 + 8 i
  ;; (low half), 20 + 8 i (high half).
  (or (. data offset) 0))

(fn run [rows data]
  "The verdict of the filter `rows` ([code jt jf k]) on `data` (offset -> word)."
  (var (pc acc verdict) (values 1 0 nil))
  (var steps 0)
  (while (not verdict)
    (set steps (+ steps 1))
    (assert (< steps 10000) "the filter loops")
    (let [[code jt jf k] (assert (. rows pc) (.. "jumped past the end to row " pc))]
      (case code
        0x20 (do (set acc (word data k)) (set pc (+ pc 1)))
        0x15 (set pc (+ pc 1 (if (= acc k) jt jf)))
        0x35 (set pc (+ pc 1 (if (>= acc k) jt jf)))
        0x06 (set verdict (assert (. verdicts k) (.. "unknown return " k)))
        _ (error (.. "unknown instruction " code)))))
  verdict)

(fn call [nr ?args ?arch]
  (let [data {0 nr 4 (or ?arch audit-arch-x64)}]
    (each [i a (ipairs (or ?args []))]
      (tset data (+ 16 (* 8 (- i 1))) a))
    (run (confine.filter-program) data)))

(describe "confine: the seccomp filter is an allow list"
  (fn []
    (it "allows what LuaJIT, libc and the protocol use"
      (fn []
        ;; read, write, close, fstat, mmap, mprotect, munmap, brk, rt_sigreturn,
        ;; clock_gettime, getrusage, futex, exit_group, newfstatat
        (each [_ nr (ipairs [0 1 3 5 9 10 11 12 15 228 98 202 231 262])]
          (assert.are.equal :allow (call nr) (.. "call " nr)))))

    (it "refuses every other call, the ones a deny list missed among them"
      (fn []
        ;; open, openat, execve, clone, socket, kill, utimensat, setxattr, fsetxattr,
        ;; rt_sigqueueinfo, rt_tgsigqueueinfo, process_vm_readv, shmget, shmat, msgget,
        ;; semget, fchmodat2, a number no kernel has yet, and 0x3fffffff
        (each [_ nr (ipairs [2 257 59 56 41 62 280 188 190 129 297 310 29 30 68 64 452 600
                             0x3fffffff])]
          (assert.are.equal :eperm (call nr) (.. "call " nr)))))

    (it "allows ioctl for TCGETS and TIOCGWINSZ only (never TIOCSTI)"
      (fn []
        (assert.are.equal :allow (call 16 [1 0x5401]))
        (assert.are.equal :allow (call 16 [1 0x5413]))
        (assert.are.equal :eperm (call 16 [0 0x5412]))
        (assert.are.equal :eperm (call 16 [0 0x541c]))))

    (it "allows prlimit64 on this process only"
      (fn []
        (assert.are.equal :allow (call 302 [0 0]))
        (assert.are.equal :eperm (call 302 [1234 0]))
        ;; A pid whose low half is 0 is still another process.
        (let [data {0 302 4 audit-arch-x64 16 0 20 1}]
          (assert.are.equal :eperm (run (confine.filter-program) data)))))

    (it "kills on another architecture and on the x32 ABI"
      (fn []
        (assert.are.equal :kill (call 0 [] 0x40000003))
        (assert.are.equal :kill (call (+ 0x40000000 1)))))))

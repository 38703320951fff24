;; What the scene worker (src/scene/worker-main.fnl) gives up before it reads a scene,
;; through LuaJIT's FFI on Linux; each is enforced by the kernel, whatever the scene's
;; code does:
;;
;; - address space (RLIMIT_AS): one allocation past it fails ("not enough memory"),
;;   however it is made (string.rep with a number, one `..` of many big strings);
;; - CPU time (RLIMIT_CPU), set again before each request to the time used so far plus
;;   that request's allowance: past it the kernel ends the process (SIGXCPU), even in a
;;   C call the step counter never sees; no core file (RLIMIT_CORE 0);
;; - files: none can be opened or created (RLIMIT_NOFILE 0). Not RLIMIT_FSIZE: it
;;   also holds for the standard error the worker shares with the app, and a Fennel
;;   warning written there, when it is a file, would end the worker (SIGXFSZ);
;; - a session of its own (setsid): no controlling terminal, so no terminal signals
;;   reach it and no ioctl can push input into the user's terminal;
;; - no new privileges (PR_SET_NO_NEW_PRIVS), then a seccomp filter (x86-64) that is an
;;   allow list: the calls LuaJIT, libc and the worker's protocol make once it serves
;;   (`allowed-x64` below, each with why), and EPERM for every other call. So a call
;;   nobody thought of (changing a file's times or attributes, signalling a process
;;   through rt_sigqueueinfo, reading another's memory, SysV shared memory, a socket)
;;   is refused too, where a deny list lets through whatever it does not name.
;;
;; Landlock would say "no writes below /" more directly, but it needs kernel 5.13 and
;; an LSM list that names it (this machine's kernel offers no /sys/kernel/security);
;; seccomp has been in every Linux kernel since 3.5 and is what browsers' renderer
;; processes use. The list was drawn from strace of a worker serving loads and frames
;; of functions of time, under LÖVE and under LuaJIT.

;; `pairs` under another name: a loop over `pairs` by that name is LuaJIT's ITERN,
;; which Debian 12's LuaJIT ends early once despecialised (see src/util/wire.fnl).
(local each-pair pairs)

(local libc (require :src.util.libc))
(local ffi libc.ffi)

(local native
  (when (and ffi (= ffi.os :Linux))
    (libc.declare [:rm_rlimit_t :setrlimit :getrlimit :rm_rusage_t :getrusage :prctl :setsid
                   :rm_sock_filter_t :rm_sock_fprog_t :strerror])))

(local rlimit {:cpu 0 :fsize 1 :core 4 :nofile 7 :as 9})

;; x86-64 system calls the filter allows (numbers from asm/unistd_64.h), and why.
(local allowed-x64
  {;; The protocol: frames on stdin and stdout (a socket), warnings on stderr; stdio
   ;; looks at a stream before its first use (fstat, lseek).
   :read 0 :write 1 :readv 19 :writev 20 :close 3 :fstat 5 :newfstatat 262 :lseek 8
   ;; Memory: LuaJIT's allocator and its JIT's machine code (mprotect to and from
   ;; PROT_EXEC), libc's malloc.
   :mmap 9 :munmap 11 :mremap 25 :mprotect 10 :brk 12 :madvise 28
   ;; Signals of its own (LuaJIT's and libc's handlers; SIGXCPU ends it).
   :rt_sigaction 13 :rt_sigprocmask 14 :rt_sigreturn 15 :sigaltstack 131
   :restart_syscall 219
   ;; Time: the deadlines and the clock a scene reads (the vDSO makes most of these
   ;; without a call), and CPU used so far (confine's limit-cpu! before each request).
   :clock_gettime 228 :clock_getres 229 :gettimeofday 96 :time 201 :getrusage 98
   :nanosleep 35 :clock_nanosleep 230
   ;; Its own identity, locks and randomness (libc).
   :getpid 39 :gettid 186 :futex 202 :sched_yield 24 :getrandom 318
   ;; Its own limits: getrlimit, and prlimit64 on this process only (checked below).
   :getrlimit 97
   :exit 60 :exit_group 231})
(local ioctl-x64 16)           ; allowed for the two requests below only
(local ioctl-allowed
  ;; TCGETS (isatty) and TIOCGWINSZ: what stdio asks of a stream; never TIOCSTI.
  [0x5401 0x5413])
(local prlimit64-x64 302)      ; allowed on this process only (glibc's setrlimit uses it)
(local audit-arch-x64 0xc000003e)

(fn set-limit! [name cur ?max]
  (let [r (ffi.new "rm_rlimit_t")]
    (native.getrlimit (. rlimit name) r)
    (set r.cur cur)
    (when ?max (set r.max ?max))
    (if (= 0 (native.setrlimit (. rlimit name) r)) true
        (values nil (.. "RLIMIT_" (name:upper) ": " (libc.error-text))))))

(fn cpu-used []
  "Seconds of CPU this process has used (user and system)."
  (let [u (ffi.new "rm_rusage_t")]
    (native.getrusage 0 u)
    (+ (tonumber u.utime.sec) (tonumber u.stime.sec)
       (* 1e-6 (+ (tonumber u.utime.usec) (tonumber u.stime.usec))))))

(fn limit-cpu! [seconds]
  "Let this process use at most `seconds` more of CPU (whole seconds, rounded up),
after which the kernel ends it. True, or nil and a message."
  (if native
      (set-limit! :cpu (math.ceil (+ (cpu-used) seconds)))
      (values nil "no FFI")))

;; Classic BPF, as seccomp reads it.
(local bpf {:ld-abs 0x20 :jeq 0x15 :jge 0x35 :ret 0x06})
(local ret {:allow 0x7fff0000 :kill 0x80000000 :eperm (+ 0x00050000 1)})

(fn filter-program []
  ;; [code jt jf k] rows: check the architecture, refuse the x32 ABI, allow each listed
  ;; call, ioctl for the listed requests and prlimit64 on this process, and answer
  ;; EPERM to everything else.
  (let [numbers (doto (icollect [_ n (each-pair allowed-x64)] n) table.sort)
        rows []
        add #(table.insert rows [$1 $2 $3 $4])
        ;; After the tests of the listed calls: the ioctl block (its test, then
        ;; `ioctl-rows`: the load, one test a request, its EPERM row), the prlimit64
        ;; block (5 rows), then the allow row and the EPERM row.
        ioctl-rows (+ 2 (length ioctl-allowed))
        tail (+ 1 ioctl-rows 5)]
    (add bpf.ld-abs 0 0 4)                     ; arch
    (add bpf.jeq 1 0 audit-arch-x64)
    (add bpf.ret 0 0 ret.kill)
    (add bpf.ld-abs 0 0 0)                     ; syscall number
    (add bpf.jge 0 1 0x40000000)
    (add bpf.ret 0 0 ret.kill)
    ;; Each listed call jumps to the allow row.
    (let [count (length numbers)]
      (each [i n (ipairs numbers)]
        (add bpf.jeq (+ (- count i) tail) 0 n)))
    ;; ioctl: its request (args[1], low half; the high half of an int is unused).
    (add bpf.jeq 0 ioctl-rows ioctl-x64)
    (add bpf.ld-abs 0 0 24)
    (each [i request (ipairs ioctl-allowed)]
      ;; Rows left to the allow row: the other requests' tests, the jump to EPERM
      ;; and the prlimit64 block.
      (add bpf.jeq (+ (- (length ioctl-allowed) i) 1 5) 0 request))
    (add bpf.ret 0 0 ret.eperm)
    ;; prlimit64 with pid 0 (this process): both halves of args[0] zero.
    (add bpf.jeq 0 5 prlimit64-x64)
    (add bpf.ld-abs 0 0 16)
    (add bpf.jeq 0 3 0)
    (add bpf.ld-abs 0 0 20)
    (add bpf.jeq 0 1 0)
    (add bpf.ret 0 0 ret.allow)
    (add bpf.ret 0 0 ret.eperm)
    rows))

(fn install-filter! []
  (let [rows (filter-program)
        prog (ffi.new "rm_sock_filter_t[?]" (length rows))]
    (each [i [code jt jf k] (ipairs rows)]
      (let [r (. prog (- i 1))]
        (set r.code code) (set r.jt jt) (set r.jf jf) (set r.k k)))
    (let [fprog (ffi.new "rm_sock_fprog_t[1]")]
      (set (. fprog 0 :len) (length rows))
      (set (. fprog 0 :filter) prog)
      ;; PR_SET_SECCOMP, SECCOMP_MODE_FILTER
      (if (= 0 (native.prctl 22 2 (ffi.cast "unsigned long" (ffi.cast "void *" fprog)) 0 0)) true
          (values nil (.. "seccomp: " (libc.error-text)))))))

(fn confine! [options]
  "Give up what the worker does not need (see the top of this file). `options`:
{:memory-mb N :cpu-seconds N}. Returns a list of what was applied and a list of
what could not be, with why."
  (let [applied [] missing []
        try (fn [what ok? why]
              (if ok? (table.insert applied what) (table.insert missing (.. what ": " (tostring why)))))]
    (if (not native)
        (table.insert missing "all: no LuaJIT FFI on Linux")
        (do
          ;; Hard limit too: the worker never needs more. (CPU keeps its hard limit,
          ;; as the soft one moves up before each request.)
          (let [bytes (* options.memory-mb 1024 1024)]
            (try (.. "address space " options.memory-mb " MB") (set-limit! :as bytes bytes)))
          (try (.. "CPU " options.cpu-seconds " s a request") (limit-cpu! options.cpu-seconds))
          (try "no core files" (set-limit! :core 0 0))
          (try "no new files" (set-limit! :nofile 0 0))
          ;; Fails only for a process group's leader, which a spawned worker is not.
          (try "no terminal" (<= 0 (native.setsid)) (libc.error-text))
          ;; PR_SET_NO_NEW_PRIVS
          (try "no new privileges" (= 0 (native.prctl 38 1 0 0 0)) (libc.error-text))
          (if (= ffi.arch :x64)
              (try "seccomp filter" (install-filter!))
              (table.insert missing (.. "seccomp filter: written for x86-64, not " ffi.arch)))))
    (values applied missing)))

{: confine! : limit-cpu! : cpu-used : filter-program}

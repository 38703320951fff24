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
;; - no new privileges (PR_SET_NO_NEW_PRIVS), then a seccomp filter (x86-64) that
;;   answers EPERM to every call that opens, creates, renames, removes or changes a
;;   file, starts a program or a process, makes a socket, signals another process or
;;   changes another's limits.
;;
;; Landlock would say "no writes below /" more directly, but it needs kernel 5.13 and
;; an LSM list that names it (this machine's kernel offers no /sys/kernel/security);
;; seccomp has been in every Linux kernel since 3.5 and is what browsers' renderer
;; processes use. The filter is a deny list: the worker needs only memory, its socket
;; and the clock, and a deny list cannot break LuaJIT's or libc's own calls.

(local libc (require :src.util.libc))
(local ffi libc.ffi)

(local native
  (when (and ffi (= ffi.os :Linux))
    (libc.declare [:rm_rlimit_t :setrlimit :getrlimit :rm_rusage_t :getrusage :prctl
                   :rm_sock_filter_t :rm_sock_fprog_t :strerror])))

(local rlimit {:cpu 0 :fsize 1 :core 4 :nofile 7 :as 9})

;; x86-64 system calls the filter refuses (numbers from asm/unistd_64.h).
(local denied-x64
  {:open 2 :openat 257 :openat2 437 :creat 85 :rename 82 :renameat 264 :renameat2 316
   :unlink 87 :unlinkat 263 :mkdir 83 :mkdirat 258 :rmdir 84 :link 86 :linkat 265
   :symlink 88 :symlinkat 266 :chmod 90 :fchmod 91 :fchmodat 268 :chown 92 :fchown 93
   :lchown 94 :fchownat 260 :truncate 76 :ftruncate 77 :mknod 133 :mknodat 259
   :execve 59 :execveat 322 :fork 57 :vfork 58 :clone 56 :clone3 435 :socket 41
   :connect 42 :bind 49 :listen 50 :accept 43 :accept4 288 :ptrace 101 :kill 62
   :tkill 200 :tgkill 234 :process_vm_writev 311 :setpriority 141 :mount 165
   :io_uring_setup 425 :memfd_create 319 :name_to_handle_at 303 :open_by_handle_at 304})
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
  ;; [code jt jf k] rows: check the architecture, refuse the x32 ABI, then each denied
  ;; call, and prlimit64 on any other process.
  (let [numbers (doto (icollect [_ n (pairs denied-x64)] n) table.sort)
        rows []
        add #(table.insert rows [$1 $2 $3 $4])]
    (add bpf.ld-abs 0 0 4)                     ; arch
    (add bpf.jeq 1 0 audit-arch-x64)
    (add bpf.ret 0 0 ret.kill)
    (add bpf.ld-abs 0 0 0)                     ; syscall number
    (add bpf.jge 0 1 0x40000000)
    (add bpf.ret 0 0 ret.kill)
    ;; Each test jumps to the EPERM return at the end when it matches.
    (let [count (length numbers)]
      (each [i n (ipairs numbers)]
        ;; rows after this one before the deny row: the rest of the tests, the
        ;; prlimit64 block (5 rows) and the allow row.
        (add bpf.jeq (+ (- count i) 5 1) 0 n)))
    (add bpf.jeq 0 4 prlimit64-x64)
    (add bpf.ld-abs 0 0 16)                    ; args[0], low half: the pid
    (add bpf.jeq 0 3 0)
    (add bpf.ld-abs 0 0 20)                    ; high half
    (add bpf.jeq 0 1 0)
    ;; Not a prlimit64 on another process (the jumps above land on the deny row when
    ;; the pid is not 0; a prlimit64 on this process falls through to allow).
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
          ;; PR_SET_NO_NEW_PRIVS
          (try "no new privileges" (= 0 (native.prctl 38 1 0 0 0)) (libc.error-text))
          (if (= ffi.arch :x64)
              (try "seccomp filter" (install-filter!))
              (table.insert missing (.. "seccomp filter: written for x86-64, not " ffi.arch)))))
    (values applied missing)))

{: confine! : limit-cpu! : cpu-used : filter-program}
